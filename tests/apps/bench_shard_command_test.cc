// `aperture bench gap --shard K/N` and `aperture bench merge` end to end: the merge of three
// shards equals the whole run trial by trial (every figure of summary.json and every cell of
// trials.csv but the measured wall and CPU times), and bad shard sets and flags are refused with
// exit 1 (data) or 2 (usage). Ground-truth trials without cameras keep this to seconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "experiments/bench/monte_carlo_bench_registry.h"
#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

const std::string kBench =
    "bench gap --trials 4 --seed 3 --autopilot ground_truth --duration 6 --max-roll-deg 30 ";

// summary.json without what each process measures for itself (times, cost, the merge's inputs;
// the section benches' "timing").
nlohmann::json Figures(nlohmann::json summary) {
  for (const char* key : {"wall_time_s", "cost", "merged_from", "timing"}) summary.erase(key);
  for (nlohmann::json& trial : summary["per_trial"]) trial.erase("wall_time_s");
  return summary;
}

std::string FileText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// RFC 4180 rows (quoted cells may hold commas) without the columns `drop`.
std::vector<std::vector<std::string>> CsvWithout(const fs::path& path,
                                                 const std::vector<std::string>& drop) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (char c : line) {
      if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        cells.emplace_back();
      } else {
        cells.back() += c;
      }
    }
    rows.push_back(cells);
  }
  for (const std::string& name : drop) {
    if (rows.empty()) break;
    const auto it = std::find(rows[0].begin(), rows[0].end(), name);
    const std::size_t column = static_cast<std::size_t>(it - rows[0].begin());
    for (auto& row : rows) {
      if (column < row.size()) row.erase(row.begin() + static_cast<std::ptrdiff_t>(column));
    }
  }
  return rows;
}

// `bench` (arguments of `aperture`) as shards 1/N .. N/N into folder/s1 .. folder/sN, merged in
// reverse order (shards merge in any order) into folder/merged.
void RunShardsAndMerge(const std::string& bench, int shards, const fs::path& folder) {
  std::string merge = "bench merge --out " + (folder / "merged").string();
  for (int k = 1; k <= shards; ++k) {
    const fs::path shard = folder / ("s" + std::to_string(k));
    const CommandResult run = RunAperture(bench + "--shard " + std::to_string(k) + "/" +
                                          std::to_string(shards) + " --out " + shard.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    merge += " " + (folder / ("s" + std::to_string(shards + 1 - k))).string();
  }
  const CommandResult merged = RunAperture(merge);
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
}

// One test (each ctest test is its own process): the whole run, three shards, the merge and the
// refused merges share the flights.
TEST(BenchShardCommand, MergedShardsEqualTheWholeRunAndBadShardSetsAreRefused) {
  TempFolder temp("bench_shard");
  const auto dir = [&](const std::string& name) { return fs::path(temp.path()) / name; };
  // The whole run on two threads, the shards on one: neither changes a trial.
  const CommandResult whole_run =
      RunAperture(kBench + "--threads 2 --out " + dir("whole").string());
  ASSERT_EQ(whole_run.exit_code, 0) << whole_run.output;
  ASSERT_NO_FATAL_FAILURE(RunShardsAndMerge(kBench + "--threads 1 ", 3, temp.path()));
  // A shard holds its block of trials and what the merge checks.
  const nlohmann::json manifest = ReadJson(dir("s1") / "summary.json");
  EXPECT_EQ(manifest["status"], "ok");
  EXPECT_EQ(manifest["bench"], "gap");
  EXPECT_EQ(manifest["shard"]["first_trial"], 0);
  EXPECT_EQ(manifest["shard"]["trials"], 2);  // 4 trials in 3 shards: 2, 1, 1
  EXPECT_EQ(manifest["run"]["trials"], 4);
  EXPECT_EQ(manifest["configuration"]["options"]["seed"], 3);
  EXPECT_TRUE(fs::exists(dir("s1") / "trials.cbor"));

  const nlohmann::json whole = ReadJson(dir("whole") / "summary.json");
  const nlohmann::json merged = ReadJson(dir("merged") / "summary.json");
  ASSERT_EQ(merged["per_trial"].size(), 4u);
  EXPECT_EQ(whole["successes"], 4);  // ground truth flies every traverse
  // JSON text of a double is its shortest exact form: equal text = equal bits.
  EXPECT_EQ(Figures(merged).dump(), Figures(whole).dump());
  EXPECT_EQ(CsvWithout(dir("merged") / "trials.csv", {"wall_time_s"}),
            CsvWithout(dir("whole") / "trials.csv", {"wall_time_s"}));
  EXPECT_TRUE(fs::exists(dir("merged") / "report.html"));
  // Cost: the whole run's threads and CPU per trial; the merge's per shard.
  EXPECT_EQ(whole["cost"]["threads"], 2);
  EXPECT_GT(whole["cost"]["cpu_s_per_trial"].get<double>(), 0.0);
  EXPECT_EQ(merged["cost"]["threads"], 1);
  ASSERT_EQ(merged["cost"]["shards"].size(), 3u);
  EXPECT_EQ(merged["cost"]["shards"][1]["shard"], "2/3");
  EXPECT_NE(whole["code_version"].get<std::string>().find(APERTURE_VERSION_FOR_TEST),
            std::string::npos);

  // Missing trials: bad data, exit 1, and a failed summary rather than one that looks complete.
  const CommandResult missing = RunAperture("bench merge --out " + dir("bad").string() + " " +
                                            dir("s1").string() + " " + dir("s3").string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("missing trials 2..2"), std::string::npos) << missing.output;
  EXPECT_EQ(ReadJson(dir("bad") / "summary.json")["status"], "failed");

  // A shard of another configuration, named by the key that differs.
  const CommandResult other = RunAperture(
      "bench gap --trials 4 --seed 3 --autopilot ground_truth --duration 6 --max-roll-deg 20 "
      "--shard 2/3 --out " +
      dir("other2").string());
  ASSERT_EQ(other.exit_code, 0) << other.output;
  const CommandResult mixed =
      RunAperture("bench merge --out " + dir("bad_config").string() + " " + dir("s1").string() +
                  " " + dir("other2").string() + " " + dir("s3").string());
  EXPECT_EQ(mixed.exit_code, 1) << mixed.output;
  EXPECT_NE(mixed.output.find("/options/ranges/max_roll_deg: 30.0 vs 20.0"), std::string::npos)
      << mixed.output;
}

// A section bench: a trial is a section. Two LED sections in two shards merge into the whole
// run's figures and frames.csv (every tracked frame's errors), bit for bit.
TEST(BenchShardCommand, LedSectionsInShardsMergeToTheWholeRun) {
  TempFolder temp("bench_shard_led");
  const auto dir = [&](const std::string& name) { return fs::path(temp.path()) / name; };
  const std::string led = "bench led --quick --seed 3 --only merged,occlusion ";
  const CommandResult whole_run = RunAperture(led + "--out " + dir("whole").string());
  ASSERT_EQ(whole_run.exit_code, 0) << whole_run.output;
  ASSERT_NO_FATAL_FAILURE(RunShardsAndMerge(led, 2, temp.path()));
  // Sections in LedBenchSectionKeys() order, whatever the order of --only: occlusion first.
  EXPECT_EQ(ReadJson(dir("s1") / "summary.json")["run"]["trials"], 2);
  const nlohmann::json whole = ReadJson(dir("whole") / "summary.json");
  const nlohmann::json merged = ReadJson(dir("merged") / "summary.json");
  ASSERT_TRUE(whole.contains("occlusion") && whole.contains("merged")) << whole.dump();
  EXPECT_FALSE(whole.contains("accuracy"));
  EXPECT_EQ(Figures(merged).dump(), Figures(whole).dump());
  EXPECT_TRUE(merged["timing"].contains("detection"));  // over both shards' frames
  const std::string frames = FileText(dir("whole") / "frames.csv");
  EXPECT_GT(std::count(frames.begin(), frames.end(), '\n'), 80);  // 40 + 40 frames + header
  EXPECT_EQ(FileText(dir("merged") / "frames.csv"), frames);
  EXPECT_EQ(whole["cost"]["trials"], 2);
  EXPECT_GT(whole["cost"]["cpu_s_per_trial"].get<double>(), 0.0);
}

// The control bench: three sections in three shards (the recovery section's throws included)
// merge into the whole run; a shard of another vehicle configuration is refused by its key.
TEST(BenchShardCommand, ControlSectionsInShardsMergeToTheWholeRun) {
  TempFolder temp("bench_shard_control");
  const auto dir = [&](const std::string& name) { return fs::path(temp.path()) / name; };
  const std::string control = "bench control --quick --seed 2 --only drag,mixer,recovery ";
  const CommandResult whole_run =
      RunAperture(control + "--threads 2 --out " + dir("whole").string());
  ASSERT_EQ(whole_run.exit_code, 0) << whole_run.output;
  ASSERT_NO_FATAL_FAILURE(RunShardsAndMerge(control + "--threads 1 ", 3, temp.path()));
  const nlohmann::json whole = ReadJson(dir("whole") / "summary.json");
  const nlohmann::json merged = ReadJson(dir("merged") / "summary.json");
  ASSERT_TRUE(whole.contains("recovery")) << whole.dump();
  EXPECT_GT(whole["recovery"]["trials"].get<int>(), 0);
  EXPECT_EQ(Figures(merged).dump(), Figures(whole).dump());
  EXPECT_EQ(merged["inputs"]["sections"], nlohmann::json::array({"drag", "mixer", "recovery"}));
  EXPECT_TRUE(merged["timing"].contains("recovery_s"));
  EXPECT_EQ(whole["cost"]["threads"], 2);
  EXPECT_EQ(merged["cost"]["threads"], 1);

  const CommandResult other = RunAperture(
      control + "--set control.mixer=one_shot --shard 2/3 --out " + dir("other2").string());
  ASSERT_EQ(other.exit_code, 0) << other.output;
  const CommandResult mixed =
      RunAperture("bench merge --out " + dir("bad").string() + " " + dir("s1").string() + " " +
                  dir("other2").string() + " " + dir("s3").string());
  EXPECT_EQ(mixed.exit_code, 1) << mixed.output;
  EXPECT_NE(mixed.output.find("/config/control/mixer"), std::string::npos) << mixed.output;
}

// bench tags: detection, mapping and missions in two shards merge into the whole run. Left
// aside: what each process measures (median_ms per detector and family, the map's solve time,
// the planning times, the frames' ms column) and the map's sigma_m, which Ceres' covariance gives
// to the last bits only (differs between two whole runs too: compared to 1e-9 relative).
TEST(BenchShardCommand, TagsSectionsInShardsMergeToTheWholeRun) {
  TempFolder temp("bench_shard_tags");
  const auto dir = [&](const std::string& name) { return fs::path(temp.path()) / name; };
  const std::string tags = "bench tags --quick --seed 2 ";
  const CommandResult whole_run = RunAperture(tags + "--out " + dir("whole").string());
  ASSERT_EQ(whole_run.exit_code, 0) << whole_run.output;
  ASSERT_NO_FATAL_FAILURE(RunShardsAndMerge(tags, 2, temp.path()));
  nlohmann::json whole = Figures(ReadJson(dir("whole") / "summary.json"));
  nlohmann::json merged = Figures(ReadJson(dir("merged") / "summary.json"));
  for (nlohmann::json* summary : {&whole, &merged}) {
    for (auto& detector : (*summary)["detection"].items()) {
      for (auto& family : detector.value().items()) family.value().erase("median_ms");
    }
    (*summary)["mapping"].erase("map_solve_time_s");
    (*summary)["missions"].erase("timing");
  }
  ASSERT_EQ(whole["mapping"]["map_tags"].size(), merged["mapping"]["map_tags"].size());
  for (std::size_t i = 0; i < whole["mapping"]["map_tags"].size(); ++i) {
    nlohmann::json& a = whole["mapping"]["map_tags"][i];
    nlohmann::json& b = merged["mapping"]["map_tags"][i];
    if (a.contains("sigma_m") && a["sigma_m"].is_number()) {
      EXPECT_NEAR(a["sigma_m"].get<double>(), b["sigma_m"].get<double>(),
                  1e-9 * a["sigma_m"].get<double>());
    }
    a.erase("sigma_m");
    b.erase("sigma_m");
  }
  EXPECT_EQ(merged.dump(), whole.dump());
  EXPECT_EQ(CsvWithout(dir("merged") / "frames.csv", {"ms"}),
            CsvWithout(dir("whole") / "frames.csv", {"ms"}));
  EXPECT_EQ(ReadJson(dir("merged") / "summary.json")["cost"]["shards"].size(), 2u);
}

// The figures, plots and images of report.html: its <svg> and <img> elements in order (the
// tables around them hold measured times).
std::vector<std::string> ReportFigures(const fs::path& path) {
  const std::string html = FileText(path);
  std::vector<std::string> figures;
  for (const auto& [open, close] : {std::pair<std::string, std::string>{"<svg", "</svg>"},
                                    std::pair<std::string, std::string>{"<img", "/>"}}) {
    for (std::size_t at = html.find(open); at != std::string::npos; at = html.find(open, at + 1)) {
      figures.push_back(html.substr(at, html.find(close, at) + close.size() - at));
    }
  }
  return figures;
}

// bench ts2p: every unit (a detection trial with its N and size sweeps and example image, a
// depth-sweep scan, a tracking approach) in one of three shards; the merge equals the whole run
// but for what each process measures (detection and tracking times, hence the CPU tie-break of
// best_method and the acceptance's CPU budget).
TEST(BenchShardCommand, Ts2pScansInShardsMergeToTheWholeRun) {
  TempFolder temp("bench_shard_ts2p");
  const auto dir = [&](const std::string& name) { return fs::path(temp.path()) / name; };
  // 3 detection trials (2 with sweeps: examples of the ellipse and the polygon), 5 depths x 1
  // scan, 1 approach: 9 units.
  const std::string ts2p =
      "bench ts2p --trials 3 --seed 2 --methods dis_ultrafast,dis_medium --sweep-trials 2 "
      "--depth-trials 1 --tracking-trials 1 ";
  const CommandResult whole_run = RunAperture(ts2p + "--threads 2 --out " + dir("whole").string());
  ASSERT_EQ(whole_run.exit_code, 0) << whole_run.output;
  ASSERT_NO_FATAL_FAILURE(RunShardsAndMerge(ts2p + "--threads 1 ", 3, temp.path()));
  const nlohmann::json manifest = ReadJson(dir("s2") / "summary.json");
  EXPECT_EQ(manifest["run"]["trials"], 9);
  EXPECT_EQ(manifest["shard"]["first_trial"], 3);
  EXPECT_EQ(manifest["shard"]["trials"], 3);

  const auto figures = [](nlohmann::json summary) {
    summary = Figures(summary);
    for (const char* sweep : {"table_ii", "stack_sweep", "resolution_sweep", "depth_sweep"}) {
      for (nlohmann::json& series : summary[sweep]) series.erase("time_ms");
    }
    summary.erase("best_method");
    summary.erase("acceptance");
    for (const char* key :
         {"propagation_ms_mean", "propagation_ms_p95", "klt_ms_mean", "total_ms_mean"}) {
      summary["tracking"].erase(key);
    }
    return summary;
  };
  const nlohmann::json whole = ReadJson(dir("whole") / "summary.json");
  const nlohmann::json merged = ReadJson(dir("merged") / "summary.json");
  ASSERT_EQ(whole["table_ii"].size(), 2u);
  EXPECT_EQ(whole["table_ii"][1]["trials"], 3);
  EXPECT_EQ(whole["stack_sweep"].size(), 3u);  // N = 2, 4, 8 on 2 trials
  EXPECT_EQ(whole["stack_sweep"][0]["trials"], 2);
  EXPECT_EQ(whole["depth_sweep"].size(), 5u);  // Z_F 1.5 .. 4.0
  EXPECT_EQ(whole["tracking"]["approaches"], 1);
  EXPECT_EQ(figures(merged).dump(), figures(whole).dump());
  EXPECT_EQ(merged["best_method"].is_string(), true);
  // Every outcome of every series (trial, shape, scores) in the same order.
  const std::vector<std::string> times = {"flow_ms",         "stacking_ms",   "edge_aware_ms",
                                          "segmentation_ms", "safe_point_ms", "total_ms",
                                          "cpu_ms"};
  const auto whole_rows = CsvWithout(dir("whole") / "trials.csv", times);
  EXPECT_EQ(whole_rows.size(), 1u + 3 * 2 + 2 * 3 + 2 * 5 + 5 * 1) << "rows";
  EXPECT_EQ(CsvWithout(dir("merged") / "trials.csv", times), whole_rows);
  // The sweep plots, the tracking drift plot and the two example overlays, byte for byte.
  const std::vector<std::string> report_figures = ReportFigures(dir("whole") / "report.html");
  EXPECT_EQ(std::count_if(report_figures.begin(), report_figures.end(),
                          [](const std::string& f) { return f.rfind("<img", 0) == 0; }),
            2);
  EXPECT_EQ(ReportFigures(dir("merged") / "report.html"), report_figures);
  EXPECT_EQ(merged["cost"]["trials"], 9);
  EXPECT_EQ(merged["cost"]["shards"].size(), 3u);

  const CommandResult missing = RunAperture("bench merge --out " + dir("bad").string() + " " +
                                            dir("s1").string() + " " + dir("s3").string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("missing trials 3..5"), std::string::npos) << missing.output;
}

TEST(BenchShardCommand, UsageMistakesExit2) {
  TempFolder temp("bench_shard_usage");
  const fs::path out = fs::path(temp.path()) / "out";
  const std::string folder = temp.path();  // exists: only the merge's own check refuses it
  for (const std::string& arguments :
       {kBench + "--shard 0/3 --out " + out.string(), kBench + "--shard 2 --out " + out.string(),
        kBench + "--shard 5/5 --out " + out.string(),  // 5 shards for 4 trials
        "bench merge --out " + out.string(),           // no shard folder
        "bench merge --out " + out.string() + " " + (out / "no_such_shard").string(),
        "bench merge --out " + folder + " " + folder}) {  // OUT is a shard folder
    const CommandResult result = RunAperture(arguments);
    EXPECT_EQ(result.exit_code, 2) << arguments << "\n" << result.output;
  }
}

// Every `aperture bench` subcommand but `merge` is a registered Monte-Carlo bench with --shard
// or declared unsharded with a reason (MonteCarloBenchRegistry::DeclareUnsharded): a new bench
// must take a side.
TEST(BenchRegistry, EveryBenchCommandIsShardableOrDeclaredUnsharded) {
  const experiments::MonteCarloBenchRegistry registry =
      experiments::MonteCarloBenchRegistry::WithBuiltins();
  const CommandResult help = RunAperture("bench --help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  std::istringstream lines(help.output.substr(help.output.find("Subcommands:")));
  std::string line;
  std::getline(lines, line);
  int commands = 0;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string name;
    if (!(words >> name) || name == "merge") continue;
    ++commands;
    const bool unsharded = registry.unsharded().count(name) > 0;
    EXPECT_NE(registry.Contains(name), unsharded) << "bench " << name;
    const CommandResult command = RunAperture("bench " + name + " --help");
    EXPECT_EQ(command.output.find("--shard") != std::string::npos, registry.Contains(name)) << name;
  }
  EXPECT_EQ(commands, static_cast<int>(registry.Names().size() + registry.unsharded().size()));
}

TEST(BenchRegistry, ANameIsRegisteredOrDeclaredUnshardedOnce) {
  experiments::MonteCarloBenchRegistry registry =
      experiments::MonteCarloBenchRegistry::WithBuiltins();
  const experiments::MonteCarloBenchFactory factory = [](const nlohmann::json&) {
    return std::unique_ptr<experiments::MonteCarloBench>();
  };
  EXPECT_THROW(registry.Register("led", factory), std::invalid_argument);
  EXPECT_THROW(registry.DeclareUnsharded("gap", "a fixed measurement"), std::invalid_argument);
  EXPECT_THROW(registry.DeclareUnsharded("new_bench", ""), std::invalid_argument);  // no reason
  registry.DeclareUnsharded("new_bench", "a fixed measurement");
  EXPECT_EQ(registry.unsharded().at("new_bench"), "a fixed measurement");
  EXPECT_THROW(registry.Register("new_bench", factory), std::invalid_argument);  // unsharded
}

}  // namespace
}  // namespace aperture::apps::testing
