// Sharded runs and merges of Monte-Carlo benches (experiments/bench/monte_carlo_run.h) on a toy
// bench whose trials take no time: the merge of any cut equals the whole run bit for bit (NaN,
// denormals and 64-bit integers included), and each kind of bad shard set is refused naming it.
#include "experiments/bench/monte_carlo_run.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "output/interruption.h"
#include "tests/support/temp_directory_test.h"

namespace aperture::experiments {
namespace {

namespace fs = std::filesystem;

constexpr const char* kVersion = "0.1.0 (test)";

// Trial k: values drawn from (seed, k) only, with the doubles JSON text could not keep.
class ToyBench : public MonteCarloBench {
 public:
  explicit ToyBench(const nlohmann::json& configuration) : configuration_(configuration) {
    if (!configuration.contains("seed") || !configuration.contains("trials")) {
      throw std::invalid_argument("toy: needs seed and trials");
    }
  }
  const nlohmann::json& configuration() const override { return configuration_; }
  TrialRange run() const override { return {0, configuration_["trials"].get<int>()}; }
  std::vector<nlohmann::json> RunTrials(const TrialRange& trials, int,
                                        const std::function<void(int)>& done) const override {
    std::vector<nlohmann::json> records;
    for (int k = trials.first; k < trials.end(); ++k) {
      std::mt19937_64 rng(configuration_["seed"].get<std::uint64_t>() * 1000003u + k);
      records.push_back({{"trial", k},
                         {"x", std::uniform_real_distribution<double>(-1.0, 1.0)(rng)},
                         {"nan", std::numeric_limits<double>::quiet_NaN()},
                         {"denormal", std::numeric_limits<double>::denorm_min() * (k + 1)},
                         {"draw", rng()}});
      if (done) done(static_cast<int>(records.size()));
    }
    return records;
  }
  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(nlohmann::json(records));
    std::ofstream(out.Path("records.cbor"), std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    double sum = 0.0;
    for (const nlohmann::json& r : records) sum += r["x"].get<double>();
    out.summary()["sum"] = sum;
    out.summary()["trials"] = records.size();
  }
  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    return "toy: " + summary["sum"].dump();
  }

 private:
  nlohmann::json configuration_;
};

MonteCarloBenchRegistry ToyRegistry() {
  MonteCarloBenchRegistry registry;
  registry.Register("toy", [](const nlohmann::json& c) { return std::make_unique<ToyBench>(c); });
  return registry;
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

class MonteCarloRunTest : public testing::TempDirectoryTest {
 protected:
  // Runs the toy bench into folder `name` (whole when shard is empty); returns the folder.
  std::string Run(const std::string& name, const std::string& shard, std::uint64_t seed = 1,
                  int trials = 7) {
    const std::string dir = (directory_ / name).string();
    output::OutputFolder out(dir);
    MonteCarloRunOptions options;
    if (!shard.empty()) options.shard = ParseShardSpec(shard);
    options.threads = 1;
    options.code_version = kVersion;
    RunMonteCarloBench(registry_, "toy", {{"seed", seed}, {"trials", trials}}, options, out);
    out.WriteSummary(output::RunStatus::kOk);
    return dir;
  }
  // The message of the ShardMergeError a merge of `shards` throws ("" if none).
  std::string MergeError(const std::vector<std::string>& shards,
                         const std::string& version = kVersion) {
    output::OutputFolder out((directory_ / "merged").string());
    try {
      MergeMonteCarloShards(registry_, shards, version, out);
    } catch (const ShardMergeError& e) {
      return e.what();
    }
    return "";
  }

  MonteCarloBenchRegistry registry_ = ToyRegistry();
};

TEST_F(MonteCarloRunTest, MergedShardsEqualTheWholeRunBitForBit) {
  const std::string whole = Run("whole", "");
  const std::vector<std::string> shards = {Run("s3", "3/3"), Run("s1", "1/3"), Run("s2", "2/3")};
  const std::string merged = (directory_ / "merged").string();
  {
    output::OutputFolder out(merged);
    EXPECT_EQ(MergeMonteCarloShards(registry_, shards, kVersion, out),
              "toy: " + nlohmann::json::parse(ReadBytes(fs::path(whole) / "summary.json"))["sum"]
                            .dump());
    out.WriteSummary(output::RunStatus::kOk);
  }
  const std::string records = ReadBytes(fs::path(whole) / "records.cbor");
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(ReadBytes(fs::path(merged) / "records.cbor"), records);
  // NaN survived the shard files (JSON text would have made it null).
  const nlohmann::json back = nlohmann::json::from_cbor(records);
  EXPECT_TRUE(std::isnan(back[6]["nan"].get<double>()));

  const nlohmann::json summary =
      nlohmann::json::parse(ReadBytes(fs::path(merged) / "summary.json"));
  EXPECT_EQ(summary["trials"], 7);
  EXPECT_EQ(summary["code_version"], kVersion);
  ASSERT_EQ(summary["cost"]["shards"].size(), 3u);
  EXPECT_EQ(summary["cost"]["shards"][0]["shard"], "1/3");  // sorted by trial block
  EXPECT_EQ(summary["cost"]["threads"], 1);
  EXPECT_GE(summary["cost"]["cpu_time_s"].get<double>(), 0.0);
  // A whole run records its cost too.
  const nlohmann::json whole_summary =
      nlohmann::json::parse(ReadBytes(fs::path(whole) / "summary.json"));
  EXPECT_EQ(whole_summary["cost"]["threads"], 1);
  EXPECT_EQ(whole_summary["cost"]["trials"], 7);
  EXPECT_TRUE(whole_summary["cost"].contains("cpu_s_per_trial"));
}

TEST_F(MonteCarloRunTest, AShardRecordsWhatTheMergeNeeds) {
  const nlohmann::json manifest =
      nlohmann::json::parse(ReadBytes(fs::path(Run("s2", "2/3")) / "summary.json"));
  EXPECT_EQ(manifest["bench"], "toy");
  EXPECT_EQ(manifest["code_version"], kVersion);
  EXPECT_EQ(manifest["configuration"]["seed"], 1);
  EXPECT_EQ(manifest["run"]["trials"], 7);
  EXPECT_EQ(manifest["shard"]["index"], 2);
  EXPECT_EQ(manifest["shard"]["count"], 3);
  EXPECT_EQ(manifest["shard"]["first_trial"], 3);  // blocks of 3, 2, 2
  EXPECT_EQ(manifest["shard"]["trials"], 2);
  EXPECT_FALSE(manifest.contains("sum"));  // a part of a run has no figures
}

TEST_F(MonteCarloRunTest, RefusesShardsOfAnotherCodeVersion) {
  const std::string error = MergeError({Run("s1", "1/2"), Run("s2", "2/2")}, "0.1.0 (other)");
  EXPECT_NE(error.find("code versions differ"), std::string::npos) << error;
}

TEST_F(MonteCarloRunTest, RefusesDifferentConfigurationsNamingTheKey) {
  const std::string error = MergeError({Run("s1", "1/2", 1), Run("s2", "2/2", 2)});
  EXPECT_NE(error.find("configurations differ"), std::string::npos) << error;
  EXPECT_NE(error.find("/seed: 1 vs 2"), std::string::npos) << error;
}

TEST_F(MonteCarloRunTest, RefusesOverlappingTrials) {
  const std::string s1 = Run("s1", "1/2");
  const std::string error = MergeError({s1, Run("s2", "2/2"), Run("t1", "1/3")});
  EXPECT_NE(error.find("overlapping trials"), std::string::npos) << error;
}

TEST_F(MonteCarloRunTest, RefusesMissingTrialsNamingThem) {
  const std::string error = MergeError({Run("s1", "1/3"), Run("s3", "3/3")});
  EXPECT_NE(error.find("missing trials 3..4"), std::string::npos) << error;
  const std::string tail = MergeError({Run("t1", "1/3"), Run("t2", "2/3")});
  EXPECT_NE(tail.find("missing trials 5..6"), std::string::npos) << tail;
}

TEST_F(MonteCarloRunTest, RefusesAFailedShardAWholeRunAndTruncatedRecords) {
  const std::string s1 = Run("s1", "1/2");
  const std::string s2 = Run("s2", "2/2");
  {
    output::OutputFolder failed(s2, /*overwrite=*/true);  // a rerun that failed: status "failed"
    failed.WriteSummary(output::RunStatus::kFailed, "killed");
  }
  std::string error = MergeError({s1, s2});
  EXPECT_NE(error.find("did not finish"), std::string::npos) << error;

  error = MergeError({s1, Run("whole", "")});
  EXPECT_NE(error.find("not a shard"), std::string::npos) << error;

  const std::string s3 = Run("s3", "2/2");
  std::ofstream(fs::path(s3) / kShardRecordsFile, std::ios::binary | std::ios::trunc)
      .write("\x81\x01", 2);  // CBOR [1]: one record for two trials
  error = MergeError({s1, s3});
  EXPECT_NE(error.find("holds 1 records"), std::string::npos) << error;
}

// Ctrl-C during the trials (output/interruption.h): RunTrialsInOrder starts no further trial (the
// one in flight finishes), and the run writes the finished trials' records as a shard does, with
// the count, and no figures.
class StoppingBench : public ToyBench {
 public:
  using ToyBench::ToyBench;
  std::vector<nlohmann::json> RunTrials(const TrialRange& trials, int threads,
                                        const std::function<void(int)>& done) const override {
    return RunTrialsInOrder(trials, threads, done, [](int k) {
      if (k == 2) output::RequestInterruption(SIGINT);  // as Ctrl-C during trial 2
      return nlohmann::json{{"x", k}};
    });
  }
};

TEST_F(MonteCarloRunTest, InterruptedRunKeepsTheFinishedTrialsRecords) {
  MonteCarloBenchRegistry registry;
  registry.Register("stopping",
                    [](const nlohmann::json& c) { return std::make_unique<StoppingBench>(c); });
  output::ClearInterruption();
  output::OutputFolder out((directory_ / "interrupted").string());
  MonteCarloRunOptions options;
  options.threads = 1;
  options.code_version = kVersion;
  const std::string outcome =
      RunMonteCarloBench(registry, "stopping", {{"seed", 1}, {"trials", 7}}, options, out);
  const bool interrupted = output::InterruptionRequested();
  output::ClearInterruption();
  EXPECT_TRUE(interrupted);
  EXPECT_NE(outcome.find("interrupted after 3 of 7 trials"), std::string::npos) << outcome;
  const nlohmann::json& summary = out.summary();
  EXPECT_EQ(summary["trials_completed"], 3);
  EXPECT_EQ(summary["run"]["trials"], 7);
  EXPECT_EQ(summary["cost"]["trials"], 3);
  EXPECT_FALSE(summary.contains("shard"));
  EXPECT_FALSE(summary.contains("sum"));  // the bench's writer did not run
  EXPECT_FALSE(fs::exists(out.Path("records.cbor")));
  std::ifstream in(out.Path(kShardRecordsFile), std::ios::binary);
  const nlohmann::json records = nlohmann::json::from_cbor(in);
  ASSERT_EQ(records.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(records[k]["trial"], k);
    EXPECT_EQ(records[k]["x"], k);
  }
}

// RunTrialsInParallel: the records of RunTrialsInOrder, in index order, whatever order the
// trials finish in; after an interruption, only the trials that ran, still in order.
TEST(RunTrialsInParallel, RecordsInIndexOrderAsRunInOrder) {
  const auto record_of = [](int k) {
    volatile double x = 0.0;  // uneven work: later trials finish first
    for (int i = 0; i < (20 - k) * 20000; ++i) x = x + 1.0;
    return nlohmann::json{{"x", k * k}};
  };
  std::vector<int> done_counts;
  const std::vector<nlohmann::json> parallel = RunTrialsInParallel(
      {3, 12}, 2, [&done_counts](int done) { done_counts.push_back(done); }, record_of);
  const std::vector<nlohmann::json> in_order = RunTrialsInOrder({3, 12}, 1, {}, record_of);
  EXPECT_EQ(parallel, in_order);
  ASSERT_EQ(parallel.size(), 12u);
  EXPECT_EQ(parallel.front()["trial"], 3);
  EXPECT_EQ(parallel.back()["x"], 14 * 14);
  std::vector<int> expected(12);
  for (int i = 0; i < 12; ++i) expected[i] = i + 1;
  EXPECT_EQ(done_counts, expected);  // serialized, counting up

  output::ClearInterruption();
  output::RequestInterruption(SIGINT);
  const std::vector<nlohmann::json> none = RunTrialsInParallel({0, 5}, 2, {}, record_of);
  output::ClearInterruption();
  EXPECT_TRUE(none.empty());
}

}  // namespace
}  // namespace aperture::experiments
