#include "experiments/bench/monte_carlo_run.h"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <utility>

#include "output/atomic_file.h"
#include "output/interruption.h"

namespace aperture::experiments {

std::vector<nlohmann::json> RunTrialsInOrder(const TrialRange& trials, int threads,
                                             const std::function<void(int)>& on_trial_done,
                                             const std::function<nlohmann::json(int)>& record_of) {
  std::vector<nlohmann::json> records;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    for (int k = trials.first; k < trials.end() && !output::InterruptionRequested(); ++k) {
      nlohmann::json record = record_of(k);
      record["trial"] = k;
      records.push_back(std::move(record));
      if (on_trial_done) on_trial_done(static_cast<int>(records.size()));
    }
  });
  return records;
}

std::vector<nlohmann::json> RunTrialsInParallel(
    const TrialRange& trials, int threads, const std::function<void(int)>& on_trial_done,
    const std::function<nlohmann::json(int)>& record_of) {
  std::vector<nlohmann::json> slots(static_cast<std::size_t>(std::max(0, trials.count)));
  std::mutex mutex;
  int done = 0;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(0, trials.count, 1, [&](int i) {
      if (output::InterruptionRequested()) return;  // start no further trial
      nlohmann::json record = record_of(trials.first + i);
      record["trial"] = trials.first + i;
      const std::lock_guard<std::mutex> lock(mutex);
      slots[static_cast<std::size_t>(i)] = std::move(record);
      ++done;
      if (on_trial_done) on_trial_done(done);
    });
  });
  std::vector<nlohmann::json> records;
  for (nlohmann::json& record : slots) {
    if (!record.is_null()) records.push_back(std::move(record));
  }
  return records;
}

namespace {

namespace fs = std::filesystem;

// CPU time of this process, every thread [s].
double ProcessCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace

nlohmann::json MeasureTrialCost(int trials, int threads, const std::function<void(int)>& body) {
  // The thread count the trials really get: `threads`, or what oneTBB may use here (the
  // process's CPU affinity: a Slurm task's --cpus-per-task).
  const int used_threads = threads > 0 ? threads : tbb::info::default_concurrency();
  const double cpu_start_s = ProcessCpuSeconds();
  const auto wall_start = std::chrono::steady_clock::now();
  body(used_threads);
  const double cpu_s = ProcessCpuSeconds() - cpu_start_s;
  return {{"threads", used_threads},
          {"trials", trials},
          {"cpu_time_s", cpu_s},
          {"cpu_s_per_trial", trials > 0 ? cpu_s / trials : 0.0},
          {"wall_time_s",
           std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count()}};
}

namespace {

std::string HostName() {
  char name[256] = {};
  return gethostname(name, sizeof(name) - 1) == 0 ? std::string(name) : std::string();
}

nlohmann::json RangeJson(const TrialRange& range) {
  return {{"first_trial", range.first}, {"trials", range.count}};
}

struct TrialLoop {
  std::vector<nlohmann::json> records;
  nlohmann::json cost;  // MeasureTrialCost
};

TrialLoop RunTrialLoop(const MonteCarloBench& bench, const TrialRange& trials, int threads,
                       const std::function<void(int, int)>& progress) {
  TrialLoop loop;
  loop.cost = MeasureTrialCost(trials.count, threads, [&](int used_threads) {
    loop.records = bench.RunTrials(trials, used_threads, [&](int done) {
      if (progress) progress(done, trials.count);
    });
  });
  // Fewer records only when SIGINT/SIGTERM stopped the loop.
  if (static_cast<int>(loop.records.size()) > trials.count ||
      (static_cast<int>(loop.records.size()) < trials.count && !output::InterruptionRequested())) {
    throw std::logic_error("Monte-Carlo bench returned " + std::to_string(loop.records.size()) +
                           " records for " + std::to_string(trials.count) + " trials");
  }
  const int completed = static_cast<int>(loop.records.size());
  if (completed < trials.count) {  // the cost of the trials that were flown
    loop.cost["trials"] = completed;
    loop.cost["cpu_s_per_trial"] =
        completed > 0 ? loop.cost["cpu_time_s"].get<double>() / completed : 0.0;
  }
  return loop;
}

std::string CommandName(const std::string& bench) { return "bench " + bench; }

// The records of a shard (or of an interrupted run) as CBOR, in kShardRecordsFile.
void WriteTrialRecords(const std::vector<nlohmann::json>& records, output::OutputFolder& out) {
  const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(nlohmann::json(records));
  output::WriteFileAtomically(out.Path(kShardRecordsFile), std::string(bytes.begin(), bytes.end()));
}

// One shard folder as recorded by RunMonteCarloBench.
struct ShardFolder {
  std::string directory;
  nlohmann::json manifest;  // its summary.json
  TrialRange trials;
};

nlohmann::json ReadJsonFile(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw ShardMergeError(path.string() + ": cannot be read");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw ShardMergeError(path.string() + ": not valid JSON (" + e.what() + ")");
  }
}

ShardFolder ReadShardFolder(const std::string& directory) {
  const fs::path summary_path = fs::path(directory) / output::OutputFolder::kSummaryFileName;
  if (!fs::exists(summary_path)) {
    throw ShardMergeError(directory +
                          ": no summary.json; pass the --out folders of `aperture bench NAME "
                          "--shard K/N` runs (a shard still running or killed has none)");
  }
  ShardFolder shard;
  shard.directory = directory;
  shard.manifest = ReadJsonFile(summary_path);
  const nlohmann::json& m = shard.manifest;
  if (m.value("status", "") != "ok") {
    throw ShardMergeError(directory + ": the shard did not finish (status '" +
                          m.value("status", "") + "': " + m.value("error", "") +
                          "); run it again with the same command");
  }
  if (!m.contains("shard") || !m.contains("bench") || !m.contains("configuration")) {
    throw ShardMergeError(directory +
                          ": not a shard (no \"shard\" in summary.json); only the outputs of "
                          "`aperture bench NAME --shard K/N` merge");
  }
  try {
    shard.trials.first = m["shard"]["first_trial"].get<int>();
    shard.trials.count = m["shard"]["trials"].get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw ShardMergeError(directory + ": summary.json \"shard\" is incomplete (" + e.what() + ")");
  }
  return shard;
}

std::vector<nlohmann::json> ReadShardRecords(const ShardFolder& shard) {
  const fs::path path = fs::path(shard.directory) / kShardRecordsFile;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw ShardMergeError(path.string() + ": missing; the shard folder is incomplete, run the "
                          "shard again");
  }
  nlohmann::json records;
  try {
    records = nlohmann::json::from_cbor(in);
  } catch (const nlohmann::json::exception& e) {
    throw ShardMergeError(path.string() + ": not a trial record file (" + e.what() + ")");
  }
  if (!records.is_array() || static_cast<int>(records.size()) != shard.trials.count) {
    throw ShardMergeError(path.string() + ": holds " +
                          std::to_string(records.is_array() ? records.size() : 0) +
                          " records, summary.json says " + std::to_string(shard.trials.count) +
                          " trials; run the shard again");
  }
  return records.get<std::vector<nlohmann::json>>();
}

// The first difference between two configurations as "path: a vs b".
std::string FirstDifference(const nlohmann::json& a, const nlohmann::json& b) {
  const nlohmann::json patch = nlohmann::json::diff(a, b);
  if (patch.empty()) return "";
  const std::string path = patch[0].value("path", "");
  const nlohmann::json::json_pointer pointer(path);
  const std::string in_a = a.contains(pointer) ? a[pointer].dump() : "(absent)";
  const std::string in_b = b.contains(pointer) ? b[pointer].dump() : "(absent)";
  return path + ": " + in_a + " vs " + in_b;
}

void CheckShardsAgree(const std::vector<ShardFolder>& shards, const std::string& code_version) {
  const ShardFolder& first = shards.front();
  const nlohmann::json& m0 = first.manifest;
  for (const ShardFolder& shard : shards) {
    const nlohmann::json& m = shard.manifest;
    if (m["bench"] != m0["bench"]) {
      throw ShardMergeError("shards of different benches: " + first.directory + " is bench " +
                            m0["bench"].dump() + ", " + shard.directory + " is bench " +
                            m["bench"].dump());
    }
    if (m.value("code_version", "") != code_version) {
      throw ShardMergeError(
          "code versions differ: " + shard.directory + " ran aperture " +
          m.value("code_version", "(unknown)") + ", this merge is aperture " + code_version +
          "; run every shard and the merge with one build");
    }
    const std::string difference = FirstDifference(m0["configuration"], m["configuration"]);
    if (!difference.empty()) {
      throw ShardMergeError("configurations differ between " + first.directory + " and " +
                            shard.directory + " at " + difference +
                            "; shards of one run share every option but --shard and --threads");
    }
  }
}

// The shards' blocks, sorted, must tile `run` exactly.
void CheckCoverage(const std::vector<ShardFolder>& sorted, const TrialRange& run) {
  int next = run.first;
  const ShardFolder* previous = nullptr;
  for (const ShardFolder& shard : sorted) {
    if (shard.trials.first < next) {
      throw ShardMergeError("overlapping trials: " + shard.directory + " has trials " +
                            std::to_string(shard.trials.first) + ".." +
                            std::to_string(shard.trials.end() - 1) + ", " +
                            (previous ? previous->directory : std::string("the run")) +
                            " already covers up to " + std::to_string(next - 1) +
                            "; pass each shard once");
    }
    if (shard.trials.first > next) {
      throw ShardMergeError("missing trials " + std::to_string(next) + ".." +
                            std::to_string(shard.trials.first - 1) + " of the run's " +
                            std::to_string(run.first) + ".." + std::to_string(run.end() - 1) +
                            "; pass the shard folder that flew them");
    }
    next = shard.trials.end();
    previous = &shard;
  }
  if (next != run.end()) {
    throw ShardMergeError("missing trials " + std::to_string(next) + ".." +
                          std::to_string(run.end() - 1) + " of the run's " +
                          std::to_string(run.first) + ".." + std::to_string(run.end() - 1) +
                          "; pass the shard folder that flew them");
  }
}

}  // namespace

std::string RunMonteCarloBench(const MonteCarloBenchRegistry& benches, const std::string& name,
                               const nlohmann::json& configuration,
                               const MonteCarloRunOptions& options, output::OutputFolder& out,
                               const std::function<void(int, int)>& progress) {
  if (options.threads < 0) {
    throw std::invalid_argument("--threads " + std::to_string(options.threads) +
                                ": must be >= 0 (0 = all cores)");
  }
  const std::unique_ptr<MonteCarloBench> bench = benches.Create(name, configuration);
  nlohmann::json& summary = out.summary();
  summary["command"] = CommandName(name);
  summary["code_version"] = options.code_version;
  const TrialRange run = bench->run();
  const TrialRange part = options.shard ? ShardTrials(*options.shard, run) : run;
  TrialLoop loop = RunTrialLoop(*bench, part, options.threads, progress);
  const int completed = static_cast<int>(loop.records.size());
  if (!options.shard && completed == run.count) {
    summary["cost"] = loop.cost;  // before the writer: its report shows the summary
    bench->WriteOutputs(loop.records, out);
    return bench->DescribeOutcome(summary);
  }
  // A shard, or a run that SIGINT/SIGTERM cut short: the trial records and the manifest, no
  // figures (the trials of a part of a run are no result).
  WriteTrialRecords(loop.records, out);
  loop.cost["host"] = HostName();
  summary["bench"] = name;
  summary["configuration"] = bench->configuration();
  summary["run"] = RangeJson(run);
  if (options.shard) {
    summary["shard"] = {{"index", options.shard->index},
                        {"count", options.shard->count},
                        {"first_trial", part.first},
                        {"trials", part.count}};
  }
  summary["records"] = kShardRecordsFile;
  summary["trials_completed"] = completed;
  summary["cost"] = loop.cost;
  if (completed < part.count) {
    return "interrupted after " + std::to_string(completed) + " of " + std::to_string(part.count) +
           " trials; their records are in " + out.Path(kShardRecordsFile);
  }
  return "shard " + ToString(*options.shard) + ": trials " + std::to_string(part.first) + ".." +
         std::to_string(part.end() - 1) + " of " + std::to_string(run.first) + ".." +
         std::to_string(run.end() - 1) + " written to " + out.directory() +
         " (merge: aperture bench merge --out DIR SHARD_DIR...)";
}

std::string MergeMonteCarloShards(const MonteCarloBenchRegistry& benches,
                                  const std::vector<std::string>& shard_dirs,
                                  const std::string& code_version, output::OutputFolder& out) {
  if (shard_dirs.empty()) throw std::invalid_argument("bench merge: no shard folder given");
  std::vector<ShardFolder> shards;
  for (const std::string& directory : shard_dirs) shards.push_back(ReadShardFolder(directory));
  CheckShardsAgree(shards, code_version);
  const nlohmann::json& m0 = shards.front().manifest;
  const std::string name = m0["bench"].get<std::string>();
  std::unique_ptr<MonteCarloBench> bench;
  try {
    bench = benches.Create(name, m0["configuration"]);
  } catch (const std::invalid_argument& e) {
    throw ShardMergeError(shards.front().directory + ": its configuration does not build bench '" +
                          name + "': " + e.what());
  }
  const std::string changed = FirstDifference(m0["configuration"], bench->configuration());
  if (!changed.empty()) {
    throw ShardMergeError("the configuration recorded by the shards differs from the one it "
                          "builds now at " + changed +
                          " (a --config file changed since the shards ran?); merge where the "
                          "shards' inputs are as they were");
  }
  std::sort(shards.begin(), shards.end(), [](const ShardFolder& a, const ShardFolder& b) {
    return a.trials.first < b.trials.first;
  });
  const TrialRange run = bench->run();
  CheckCoverage(shards, run);

  std::vector<nlohmann::json> records;
  nlohmann::json shard_costs = nlohmann::json::array();
  nlohmann::json threads = nlohmann::json::array();
  double cpu_s = 0.0;
  for (const ShardFolder& shard : shards) {
    std::vector<nlohmann::json> part = ReadShardRecords(shard);
    records.insert(records.end(), std::make_move_iterator(part.begin()),
                   std::make_move_iterator(part.end()));
    nlohmann::json cost = shard.manifest["cost"];
    cost["shard"] = ToString({shard.manifest["shard"]["index"].get<int>(),
                              shard.manifest["shard"]["count"].get<int>()});
    cost["first_trial"] = shard.trials.first;
    cost["folder_wall_time_s"] = shard.manifest.value("wall_time_s", 0.0);
    cpu_s += cost.value("cpu_time_s", 0.0);
    threads.push_back(cost.value("threads", 0));
    shard_costs.push_back(cost);
  }
  nlohmann::json& summary = out.summary();
  summary["command"] = CommandName(name);
  summary["code_version"] = code_version;
  summary["merged_from"] = shard_dirs;
  const bool one_thread_count =
      std::all_of(threads.begin(), threads.end(), [&](const nlohmann::json& t) {
        return t == threads.front();
      });
  summary["cost"] = {{"threads", one_thread_count ? threads.front() : threads},
                     {"trials", run.count},
                     {"cpu_time_s", cpu_s},
                     {"cpu_s_per_trial", cpu_s / run.count},
                     {"shards", shard_costs}};
  bench->WriteOutputs(records, out);
  return bench->DescribeOutcome(summary);
}

}  // namespace aperture::experiments
