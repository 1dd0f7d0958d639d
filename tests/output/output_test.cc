#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/atomic_file.h"
#include "output/background_video_writer.h"
#include "output/base64.h"
#include "output/csv_writer.h"
#include "output/html_report.h"
#include "output/json_eigen.h"
#include "output/json_fields.h"
#include "output/output_folder.h"
#include "output/progress_bar.h"
#include "output/svg_plot.h"
#include "output/tum_trajectory_writer.h"
#include "output/video_writer.h"

namespace aperture::output {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class OutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("aperture_output_test_" +
                  std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  static std::string ReadFile(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
  }

  // Names of all files in `directory` (non-recursive).
  static std::vector<std::string> ListFiles(const fs::path& directory) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(directory)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  static std::vector<std::string> SplitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) lines.push_back(line);
    return lines;
  }

  static std::vector<std::string> Split(const std::string& line, char separator) {
    std::vector<std::string> fields;
    std::istringstream stream(line);
    for (std::string field; std::getline(stream, field, separator);) fields.push_back(field);
    return fields;
  }

  fs::path directory_;
};

// ---- FieldsToJson / FieldsFromJson -------------------------------------------------------------

enum class Colour { kRed, kGreen };
struct FieldsRecord {
  int count = 0;
  double t_s = 0.0;
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
  Colour colour = Colour::kRed;
  std::string note;
};
const JsonEnumNames<Colour> kColourNames = {{"red", Colour::kRed}, {"green", Colour::kGreen}};
constexpr auto kFieldsRecordFields = [](auto& f, auto& r) {
  f("count", r.count);
  f("t_s", r.t_s);
  f("p_W_m", r.p_W_m);
  f("colour", r.colour, kColourNames);
  f("note", r.note);
};

TEST(JsonFields, RoundTripEveryFieldKindByKey) {
  const FieldsRecord record{7, 0.25, Eigen::Vector3d(1.0, -2.0, 3.5), Colour::kGreen, "x"};
  const nlohmann::json json = FieldsToJson(record, kFieldsRecordFields);
  EXPECT_EQ(json.at("count"), 7);
  EXPECT_EQ(json.at("p_W_m"), nlohmann::json({1.0, -2.0, 3.5}));
  EXPECT_EQ(json.at("colour"), "green");
  const FieldsRecord back = FieldsFromJson<FieldsRecord>(json, kFieldsRecordFields);
  EXPECT_EQ(back.count, 7);
  EXPECT_EQ(back.t_s, 0.25);
  EXPECT_EQ(back.p_W_m, record.p_W_m);
  EXPECT_EQ(back.colour, Colour::kGreen);
  EXPECT_EQ(back.note, "x");
}

TEST(JsonFields, MissingKeysWrongVectorsAndUnknownNamesThrow) {
  nlohmann::json json = FieldsToJson(FieldsRecord{}, kFieldsRecordFields);
  nlohmann::json missing = json;
  missing.erase("t_s");
  EXPECT_THROW(FieldsFromJson<FieldsRecord>(missing, kFieldsRecordFields),
               nlohmann::json::exception);
  nlohmann::json short_vector = json;
  short_vector["p_W_m"] = {1.0, 2.0};
  EXPECT_THROW(FieldsFromJson<FieldsRecord>(short_vector, kFieldsRecordFields),
               std::invalid_argument);
  json["colour"] = "blue";
  try {
    FieldsFromJson<FieldsRecord>(json, kFieldsRecordFields);
    ADD_FAILURE() << "an unknown enum name was read";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("colour"));
    EXPECT_THAT(e.what(), HasSubstr("blue"));
  }
}

// ---- OutputFolder / summary.json ---------------------------------------------------------------

TEST_F(OutputTest, SummaryRoundTripsWithOkStatus) {
  OutputFolder out((directory_ / "nested" / "run").string());  // parents are created
  out.summary()["inputs"]["sequence"] = "gap_01";
  out.summary()["counts"]["frames"] = 120;
  out.summary()["timing_ms"] = {{"gap_detector", 3.25}, {"tracker", 0.125}};
  Eigen::Matrix<double, 2, 3> R;
  R << 1, 2, 3, 4, 5, 6;
  out.summary()["p_W_m"] = EigenToJson(Eigen::Vector3d(0.5, -1.0, 2.0));
  out.summary()["R"] = EigenToJson(R);
  const std::string path = out.WriteSummary(RunStatus::kOk);
  EXPECT_EQ(path, (directory_ / "nested" / "run" / "summary.json").string());
  const nlohmann::json read = nlohmann::json::parse(ReadFile(path));
  EXPECT_EQ(read["status"], "ok");
  EXPECT_FALSE(read.contains("error"));
  EXPECT_EQ(read["inputs"]["sequence"], "gap_01");
  EXPECT_EQ(read["counts"]["frames"], 120);
  EXPECT_EQ(read["timing_ms"]["tracker"].get<double>(), 0.125);
  EXPECT_GE(read["wall_time_s"].get<double>(), 0.0);
  EXPECT_EQ(read["p_W_m"], nlohmann::json::parse("[0.5, -1.0, 2.0]"));
  EXPECT_EQ(read["R"], nlohmann::json::parse("[[1, 2, 3], [4, 5, 6]]"));  // rows
  // Atomic write: only the summary remains, no temporary or probe file.
  EXPECT_EQ(ListFiles(directory_ / "nested" / "run"), std::vector<std::string>{"summary.json"});
}

TEST_F(OutputTest, FailedSummaryCarriesError) {
  OutputFolder out(directory_.string());
  out.summary()["counts"]["frames"] = 7;
  out.WriteSummary(RunStatus::kFailed, "camera 'cam0' calibration file missing");
  const nlohmann::json read = nlohmann::json::parse(ReadFile(out.Path("summary.json")));
  EXPECT_EQ(read["status"], "failed");
  EXPECT_EQ(read["error"], "camera 'cam0' calibration file missing");
  EXPECT_EQ(read["counts"]["frames"], 7);  // partial figures are kept, clearly marked failed
  EXPECT_THROW(out.WriteSummary(RunStatus::kFailed, ""), std::invalid_argument);
}

TEST_F(OutputTest, RunAndWriteSummaryRecordsFailureAndRethrows) {
  OutputFolder out(directory_.string());
  EXPECT_THROW(RunAndWriteSummary(out,
                                  [&] {
                                    out.summary()["counts"]["frames"] = 3;
                                    throw std::invalid_argument("image 'f3.png' unreadable");
                                  }),
               std::invalid_argument);
  nlohmann::json read = nlohmann::json::parse(ReadFile(out.Path("summary.json")));
  EXPECT_EQ(read["status"], "failed");
  EXPECT_EQ(read["error"], "image 'f3.png' unreadable");
  EXPECT_EQ(read["counts"]["frames"], 3);

  RunAndWriteSummary(out, [&] { out.summary()["counts"]["frames"] = 4; });
  read = nlohmann::json::parse(ReadFile(out.Path("summary.json")));
  EXPECT_EQ(read["status"], "ok");
  EXPECT_FALSE(read.contains("error"));  // a stale error from before must not survive
}

TEST_F(OutputTest, StaleSummaryIsRemovedWhenFolderIsReused) {
  {
    OutputFolder first(directory_.string());
    first.WriteSummary(RunStatus::kOk);
  }
  ASSERT_TRUE(fs::exists(directory_ / "summary.json"));
  OutputFolder second(directory_.string());
  // A second run that crashes now must not leave the first run's "ok" behind.
  EXPECT_FALSE(fs::exists(directory_ / "summary.json"));
}

// A reused --out folder (issue 18): an earlier run's outputs are refused unless --overwrite, which
// removes exactly what that run created (its summary.json "files") and leaves other files alone.
TEST_F(OutputTest, FolderWithAnEarlierRunsOutputsIsRefusedUnlessOverwrite) {
  {
    OutputFolder first(directory_.string());
    std::ofstream(first.Path("gap.csv")) << "t\n";
    fs::create_directories(first.Path("images"));
    std::ofstream(first.Path("images/000000.png")) << "x";
    first.WriteSummary(RunStatus::kOk);
  }
  EXPECT_EQ(nlohmann::json::parse(ReadFile(directory_ / "summary.json"))["files"],
            nlohmann::json::parse(R"(["gap.csv", "images"])"));
  std::ofstream(directory_ / "notes.txt") << "mine";  // written by the user after that run
  try {
    OutputFolder refused(directory_.string());
    FAIL() << "a folder with an earlier run's outputs must be refused";
  } catch (const FolderInUseError& e) {
    EXPECT_THAT(e.what(), HasSubstr(directory_.string()));
    EXPECT_THAT(e.what(), HasSubstr("--overwrite"));
  }
  EXPECT_TRUE(fs::exists(directory_ / "gap.csv"));  // refusing touches nothing

  OutputFolder second(directory_.string(), /*overwrite=*/true);
  EXPECT_EQ(ListFiles(directory_), std::vector<std::string>{"notes.txt"});
  std::ofstream(second.Path("poses.csv")) << "t\n";
  second.WriteSummary(RunStatus::kOk);
  EXPECT_EQ(nlohmann::json::parse(ReadFile(directory_ / "summary.json"))["files"],
            nlohmann::json::parse(R"(["poses.csv"])"));  // not the user's notes.txt
}

TEST_F(OutputTest, FolderOfForeignFilesIsRefusedEvenWithOverwrite) {
  fs::create_directories(directory_);
  std::ofstream(directory_ / "thesis.tex") << "x";
  EXPECT_THROW(OutputFolder(directory_.string()), FolderInUseError);
  try {
    OutputFolder out(directory_.string(), /*overwrite=*/true);
    FAIL() << "--overwrite must not guess what to delete";
  } catch (const FolderInUseError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no summary.json"));
  }
  EXPECT_TRUE(fs::exists(directory_ / "thesis.tex"));
}

// --out naming a file is a usage mistake (exit 2 through FolderInUseError), even with --overwrite.
TEST_F(OutputTest, FileInPlaceOfTheFolderIsRefusedAndKept) {
  fs::create_directories(directory_.parent_path());
  std::ofstream(directory_) << "mine";
  for (const bool overwrite : {false, true}) {
    try {
      OutputFolder out(directory_.string(), overwrite);
      FAIL() << "a file given as --out must be refused";
    } catch (const FolderInUseError& e) {
      EXPECT_THAT(e.what(), HasSubstr(directory_.string()));
      EXPECT_THAT(e.what(), HasSubstr("is a file"));
    }
  }
  EXPECT_EQ(ReadFile(directory_), "mine");
}

TEST_F(OutputTest, FolderOfARunThatWroteNothingButItsSummaryIsReused) {
  {
    OutputFolder failed(directory_.string());
    failed.WriteSummary(RunStatus::kFailed, "--set gap.rol_deg=3: unknown key");
  }
  OutputFolder again(directory_.string());  // the typo fixed, same --out: no --overwrite needed
  EXPECT_TRUE(ListFiles(directory_).empty());
}

TEST_F(OutputTest, UnwritableFolderErrorNamesThePath) {
  fs::create_directories(directory_);
  std::ofstream(directory_ / "regular_file") << "x";
  const std::string bad = (directory_ / "regular_file" / "out").string();
  try {
    OutputFolder out(bad);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(bad));
  }
}

TEST_F(OutputTest, AtomicFileDiscardsOnExceptionAndCommitsOtherwise) {
  fs::create_directories(directory_);
  const fs::path path = directory_ / "data.txt";
  try {
    AtomicFile file(path.string());
    file.stream() << "half written";
    throw std::runtime_error("run failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(ListFiles(directory_).empty());  // neither data.txt nor data.txt.tmp
  {
    AtomicFile file(path.string());
    file.stream() << "complete";
    EXPECT_TRUE(fs::exists(file.temporary_path()));
    EXPECT_FALSE(fs::exists(path));  // invisible under its final name until committed
  }
  EXPECT_EQ(ReadFile(path), "complete");
  EXPECT_EQ(ListFiles(directory_), std::vector<std::string>{"data.txt"});
}

// ---- CSV
// -----------------------------------------------------------------------------------------

TEST_F(OutputTest, CsvNumbersReadBackExactly) {
  fs::create_directories(directory_);
  const std::vector<std::vector<double>> rows = {
      {0.1, 1.0 / 3.0, -2.5e-300},
      {123456789.123456789, std::nextafter(1.0, 2.0), 0.0},
      {std::nan(""), HUGE_VAL, -HUGE_VAL},
  };
  const std::string path = (directory_ / "series.csv").string();
  {
    CsvWriter csv(path, {"t_s", "value, with comma", "z"});
    for (const auto& row : rows) csv.WriteRow(row);
    csv.WriteCells({CsvCell(4.0), CsvCell(std::string("say \"hi\"")), CsvCell(-1.0)});
    EXPECT_THROW(csv.WriteRow({1.0, 2.0}), std::invalid_argument);  // wrong width
    csv.Close();
  }
  const std::vector<std::string> lines = SplitLines(ReadFile(path));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "t_s,\"value, with comma\",z");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::vector<std::string> fields = Split(lines[r + 1], ',');
    ASSERT_EQ(fields.size(), 3u);
    for (std::size_t c = 0; c < 3; ++c) {
      const double parsed = std::strtod(fields[c].c_str(), nullptr);
      if (std::isnan(rows[r][c])) {
        EXPECT_TRUE(std::isnan(parsed));
      } else {
        EXPECT_EQ(parsed, rows[r][c]) << fields[c];  // bit-exact round trip
      }
    }
  }
  EXPECT_EQ(lines[4], "4,\"say \"\"hi\"\"\",-1");
  EXPECT_EQ(ListFiles(directory_), std::vector<std::string>{"series.csv"});
}

// ---- TUM trajectory
// ------------------------------------------------------------------------------

TEST_F(OutputTest, TumLinesParseBackToTheSamePoses) {
  fs::create_directories(directory_);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 20; ++i) {
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.linear() =
        Eigen::Quaterniond(uniform(random), uniform(random), uniform(random), uniform(random))
            .normalized()
            .toRotationMatrix();
    T_WB.translation() = Eigen::Vector3d(uniform(random), uniform(random), uniform(random)) * 10;
    poses.push_back(T_WB);
  }
  const std::string path = (directory_ / "estimate.tum").string();
  {
    TumTrajectoryWriter tum(path);
    for (std::size_t i = 0; i < poses.size(); ++i) tum.Write(0.05 * i, poses[i]);
    // Unnormalised quaternion input (w, x, y, z) = 2 * identity: must be written as unit, w last.
    tum.Write(10.0, Eigen::Vector3d(1, 2, 3), Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0));
    EXPECT_THROW(tum.Write(11.0, Eigen::Vector3d(1, 2, 3), Eigen::Quaterniond(0, 0, 0, 0)),
                 std::invalid_argument);
    tum.Close();
  }
  std::vector<std::string> lines = SplitLines(ReadFile(path));
  ASSERT_EQ(lines.size(), poses.size() + 2);
  EXPECT_EQ(lines[0][0], '#');
  for (std::size_t i = 0; i < poses.size(); ++i) {
    std::istringstream line(lines[i + 1]);
    double t, tx, ty, tz, qx, qy, qz, qw;
    ASSERT_TRUE(line >> t >> tx >> ty >> tz >> qx >> qy >> qz >> qw) << lines[i + 1];
    EXPECT_EQ(t, 0.05 * i);
    EXPECT_EQ(Eigen::Vector3d(tx, ty, tz), poses[i].translation());
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);  // normalised in double precision
    // Same rotation (q and -q are equivalent): 1e-14 allows rounding in matrix<->quaternion.
    EXPECT_TRUE(q.toRotationMatrix().isApprox(poses[i].rotation(), 1e-14));
  }
  EXPECT_EQ(lines.back(), "10 1 2 3 0 0 0 1");
}

// ---- Ticks and box statistics
// --------------------------------------------------------------------

TEST_F(OutputTest, NiceTicksCoverTheDataWithRoundSteps) {
  const std::vector<std::pair<double, double>> ranges = {
      {0.0, 1.0}, {-3.7, 12.2}, {1e-5, 3.3e-5}, {-1e6, 2.5e6}, {99.9, 100.1}, {0.013, 0.0171}};
  for (const auto& [low, high] : ranges) {
    const AxisTicks ticks = ComputeNiceTicks(low, high);
    EXPECT_LE(ticks.min(), low);
    EXPECT_GE(ticks.max(), high);
    EXPECT_GE(ticks.values.size(), 3u);
    EXPECT_LE(ticks.values.size(), 12u);
    const double mantissa = ticks.step / std::pow(10.0, std::floor(std::log10(ticks.step)));
    EXPECT_THAT(mantissa, ::testing::AnyOf(
                              ::testing::DoubleNear(1.0, 1e-9), ::testing::DoubleNear(2.0, 1e-9),
                              ::testing::DoubleNear(2.5, 1e-9), ::testing::DoubleNear(5.0, 1e-9)));
    for (const double tick : ticks.values) {
      // Every tick is an integer multiple of the step (relative 1e-9 for rounding).
      EXPECT_NEAR(tick / ticks.step, std::round(tick / ticks.step), 1e-9);
    }
  }
  EXPECT_EQ(ComputeNiceTicks(0.0, 10.0).values, (std::vector<double>{0, 2, 4, 6, 8, 10}));
  const AxisTicks constant = ComputeNiceTicks(5.0, 5.0);
  EXPECT_LT(constant.min(), 5.0);
  EXPECT_GT(constant.max(), 5.0);
  const AxisTicks empty = ComputeNiceTicks(std::nan(""), std::nan(""));
  EXPECT_LT(empty.min(), empty.max());
}

TEST_F(OutputTest, BoxStatsMatchHandComputedQuartiles) {
  // 1..9: order statistics at positions 2, 4, 6 → 3, 5, 7 (linear interpolation, exact here).
  const BoxStats stats = ComputeBoxStats({9, 1, 8, 2, 7, 3, 6, 4, 5, std::nan("")});
  EXPECT_EQ(stats.count, 9u);
  EXPECT_EQ(stats.q1, 3.0);
  EXPECT_EQ(stats.median, 5.0);
  EXPECT_EQ(stats.q3, 7.0);
  EXPECT_EQ(stats.whisker_low, 1.0);
  EXPECT_EQ(stats.whisker_high, 9.0);
  EXPECT_TRUE(stats.outliers.empty());
  // 100 is beyond q3 + 1.5 IQR = 7.5 + 1.5 * 5 (quartiles of 1..9,100 are 3.25 and 7.75).
  const BoxStats with_outlier = ComputeBoxStats({1, 2, 3, 4, 5, 6, 7, 8, 9, 100});
  EXPECT_EQ(with_outlier.outliers, std::vector<double>{100.0});
  EXPECT_EQ(with_outlier.whisker_high, 9.0);
  EXPECT_EQ(ComputeBoxStats({}).count, 0u);
}

// ---- SVG
// -----------------------------------------------------------------------------------------

// Checks that every element is closed in order (a minimal XML well-formedness check: no
// attributes containing '>' are produced by SvgPlot).
bool TagsBalance(const std::string& svg, std::string* problem) {
  std::vector<std::string> open;
  const std::regex tag("<(/?)([a-zA-Z]+)[^>]*?(/?)>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), tag); it != std::sregex_iterator();
       ++it) {
    const std::smatch& match = *it;
    if (match[3] == "/") continue;  // self-closing
    if (match[1] == "/") {
      if (open.empty() || open.back() != match[2]) {
        *problem = "unexpected </" + match[2].str() + ">";
        return false;
      }
      open.pop_back();
    } else {
      open.push_back(match[2]);
    }
  }
  *problem = open.empty() ? "" : "unclosed <" + open.back() + ">";
  return open.empty();
}

int CountOccurrences(const std::string& text, const std::string& pattern) {
  int count = 0;
  for (std::size_t at = text.find(pattern); at != std::string::npos;
       at = text.find(pattern, at + 1)) {
    ++count;
  }
  return count;
}

void ExpectWellFormedSvg(const std::string& svg) {
  EXPECT_EQ(CountOccurrences(svg, "<svg"), 1);
  EXPECT_EQ(CountOccurrences(svg, "</svg>"), 1);
  std::string problem;
  EXPECT_TRUE(TagsBalance(svg, &problem)) << problem;
  EXPECT_EQ(svg.find("nan"), std::string::npos);  // no NaN coordinates leaked
}

// Total number of "x,y" points over the polylines of `series`.
int PolylinePointCount(const std::string& svg, const std::string& series) {
  const std::regex polyline("<polyline[^>]*data-series=\"" + series + "\"[^>]*points=\"([^\"]*)\"");
  int points = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polyline);
       it != std::sregex_iterator(); ++it) {
    points += CountOccurrences((*it)[1].str(), ",");
  }
  return points;
}

std::vector<double> TickLabels(const std::string& svg, const std::string& group) {
  const std::size_t begin = svg.find("<g class=\"" + group + "\"");
  const std::size_t end = svg.find("</g>", begin);
  const std::string block = svg.substr(begin, end - begin);
  std::vector<double> values;
  const std::regex text(">([-0-9.e+]+)</text>");
  for (auto it = std::sregex_iterator(block.begin(), block.end(), text);
       it != std::sregex_iterator(); ++it) {
    values.push_back(std::stod((*it)[1].str()));
  }
  return values;
}

TEST_F(OutputTest, LinePlotSkipsNanPointsAndTicksCoverData) {
  std::vector<double> t, y, y2;
  for (int i = 0; i < 50; ++i) {
    t.push_back(0.1 * i);
    y.push_back(std::sin(0.1 * i) * 3.0 + 1.0);
    y2.push_back(i == 10 || i == 11 || i == 30 ? std::nan("") : -0.5 * i);
  }
  const std::string svg = SvgPlot({"Error <m> & more", "t [s]", "e [m]"})
                              .AddLine("sine", t, y)
                              .AddLine("ramp", t, y2)
                              .Render();
  ExpectWellFormedSvg(svg);
  EXPECT_THAT(svg, HasSubstr("Error &lt;m&gt; &amp; more"));
  EXPECT_EQ(PolylinePointCount(svg, "sine"), 50);
  EXPECT_EQ(PolylinePointCount(svg, "ramp"), 47);  // three NaN samples skipped
  // The ramp is broken at the NaNs into three separate polylines (0-9, 12-29, 31-49).
  EXPECT_EQ(CountOccurrences(svg, "data-series=\"ramp\""), 3);
  const std::vector<double> x_ticks = TickLabels(svg, "x-tick-labels");
  const std::vector<double> y_ticks = TickLabels(svg, "y-tick-labels");
  ASSERT_GE(x_ticks.size(), 2u);
  ASSERT_GE(y_ticks.size(), 2u);
  EXPECT_LE(x_ticks.front(), 0.0);
  EXPECT_GE(x_ticks.back(), 4.9);
  EXPECT_LE(y_ticks.front(), -24.5);            // min of the ramp
  EXPECT_GE(y_ticks.back(), 4.0);               // max of 3 sin + 1
  EXPECT_THAT(svg, HasSubstr(">sine</text>"));  // legend
  EXPECT_THROW(SvgPlot({"bad"}).AddLine("short", {1, 2}, {1}), std::invalid_argument);
}

TEST_F(OutputTest, TickLabelsStayDistinctAtLargeAndSmallScales) {
  // Unix timestamps (large offset, small span) and micro-scale values must not collapse into
  // identical labels; each label must read back to its tick within half a step.
  for (const double offset : {1.7e9, 0.0, 3e-6}) {
    const double span = offset == 0.0 ? 1e-5 : offset * 1e-8;
    const std::string svg =
        SvgPlot({"ticks"}).AddLine("s", {offset, offset + span}, {offset, offset + span}).Render();
    const AxisTicks ticks = ComputeNiceTicks(offset, offset + span);
    const std::vector<double> labels = TickLabels(svg, "x-tick-labels");
    ASSERT_EQ(labels.size(), ticks.values.size());
    for (std::size_t i = 0; i < labels.size(); ++i) {
      EXPECT_NEAR(labels[i], ticks.values[i], ticks.step / 2) << "offset " << offset;
    }
  }
}

TEST_F(OutputTest, ScatterEmptyAndAllNanPlotsStayWellFormed) {
  const std::string scatter =
      SvgPlot({"s"}).AddScatter("pts", {1, 2, std::nan(""), 4}, {1, 4, 9, HUGE_VAL}).Render();
  ExpectWellFormedSvg(scatter);
  EXPECT_EQ(CountOccurrences(scatter, "<circle"), 2);  // only the two finite pairs
  const std::string empty = SvgPlot({"empty"}).AddLine("none", {}, {}).Render();
  ExpectWellFormedSvg(empty);
  EXPECT_EQ(CountOccurrences(empty, "<polyline"), 0);
  const std::string nothing = SvgPlot({"nothing"}).Render();
  ExpectWellFormedSvg(nothing);
  ExpectWellFormedSvg(SvgPlot::Histogram({"h"}, {{"none", {}}}));
  ExpectWellFormedSvg(SvgPlot::BoxPlot({"b"}, {{"none", {std::nan("")}}}));
  ExpectWellFormedSvg(SvgPlot::BoxPlot({"b"}, {}));
}

TEST_F(OutputTest, HistogramCountsEveryFiniteValueOnce) {
  const std::vector<double> values = {0, 0, 1, 1, 1, 2, 3, 3, 4, std::nan("")};
  const std::string svg = SvgPlot::Histogram({"h", "v", "count"}, {{"v", values}}, 4);
  ExpectWellFormedSvg(svg);
  // Bins of width 1 over [0, 4]: [0,1) [1,2) [2,3) [3,4] → 2, 3, 1, 3.
  std::vector<int> counts;
  const std::regex bin("data-count=\"([0-9]+)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), bin); it != std::sregex_iterator();
       ++it) {
    counts.push_back(std::stoi((*it)[1].str()));
  }
  EXPECT_EQ(counts, (std::vector<int>{2, 3, 1, 3}));
  EXPECT_GE(TickLabels(svg, "y-tick-labels").back(), 3.0);
}

TEST_F(OutputTest, BoxPlotDrawsOneBoxPerNonEmptyGroup) {
  const std::string svg = SvgPlot::BoxPlot(
      {"latency", "", "ms"}, {{"gap", {1, 2, 3, 4, 50}}, {"led", {}}, {"tag", {2, 2, 2}}});
  ExpectWellFormedSvg(svg);
  EXPECT_EQ(CountOccurrences(svg, "class=\"box\""), 2);
  EXPECT_EQ(CountOccurrences(svg, "class=\"outlier\""), 1);  // 50 in "gap"
  EXPECT_EQ(CountOccurrences(svg, "class=\"category\""), 3);
  EXPECT_GE(TickLabels(svg, "y-tick-labels").back(), 50.0);
}

// ---- Base64 and HTML
// -----------------------------------------------------------------------------

TEST_F(OutputTest, Base64MatchesRfc4648Vectors) {
  const std::vector<std::pair<std::string, std::string>> vectors = {{"", ""},
                                                                    {"f", "Zg=="},
                                                                    {"fo", "Zm8="},
                                                                    {"foo", "Zm9v"},
                                                                    {"foob", "Zm9vYg=="},
                                                                    {"fooba", "Zm9vYmE="},
                                                                    {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    const std::vector<std::uint8_t> bytes(plain.begin(), plain.end());
    EXPECT_EQ(Base64Encode(bytes), encoded);
    EXPECT_EQ(Base64Decode(encoded), bytes);
  }
  EXPECT_THROW(Base64Decode("Zm9"), std::invalid_argument);
  EXPECT_THROW(Base64Decode("Zm=v"), std::invalid_argument);
  EXPECT_THROW(Base64Decode("Zm9*"), std::invalid_argument);
}

// The first image embedded as a data URI with `prefix` ("data:image/png;base64,"); empty if none.
cv::Mat DecodeFirstImage(const std::string& html, const std::string& prefix) {
  const std::size_t begin = html.find(prefix);
  if (begin == std::string::npos) return cv::Mat();
  const std::size_t data_begin = begin + prefix.size();
  const std::string encoded = html.substr(data_begin, html.find('"', data_begin) - data_begin);
  return cv::imdecode(Base64Decode(encoded), cv::IMREAD_UNCHANGED);
}

TEST_F(OutputTest, HtmlReportEmbedsPngThatDecodesToTheSameImage) {
  fs::create_directories(directory_);
  cv::Mat image(37, 53, CV_8UC3);
  cv::RNG rng(3);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  HtmlReport report("Run <gap>");
  report.AddSection("Summary");
  report.AddParagraph("5 < 7 & done");
  report.AddTable({{"status", "ok"}, {"counts", {{"frames", 120}}}, {"error_m", 0.0123456789}});
  report.AddTable(nlohmann::json::array({{{"node", "gap"}, {"ms", 3.5}}, {{"node", "led"}}}));
  report.AddSvg(SvgPlot({"p"}).AddLine("a", {0, 1}, {0, 1}).Render(), "a plot");
  report.AddImage(image, "key frame");
  const std::string path = (directory_ / "report.html").string();
  report.Write(path);
  EXPECT_EQ(ListFiles(directory_), std::vector<std::string>{"report.html"});

  const std::string html = ReadFile(path);
  EXPECT_THAT(html, HasSubstr("<title>Run &lt;gap&gt;</title>"));
  EXPECT_THAT(html, HasSubstr("5 &lt; 7 &amp; done"));
  EXPECT_THAT(html, HasSubstr("<th>counts.frames</th><td class=\"number\">120</td>"));
  EXPECT_THAT(html, HasSubstr("0.0123457"));
  // Columns are the union of keys (nlohmann::json objects iterate keys in sorted order).
  EXPECT_THAT(html, HasSubstr("<th>ms</th><th>node</th>"));
  EXPECT_THAT(html, HasSubstr("<tr><td></td><td>led</td></tr>"));
  EXPECT_EQ(CountOccurrences(html, "<svg"), 1);
  EXPECT_EQ(html.find("<script"), std::string::npos);  // self-contained, no JS
  EXPECT_EQ(html.find("http://www.w3.org/2000/svg"), html.find("xmlns=") + 7);  // only the SVG ns

  const cv::Mat decoded = DecodeFirstImage(html, "data:image/png;base64,");
  ASSERT_FALSE(decoded.empty());
  ASSERT_EQ(decoded.size(), image.size());
  ASSERT_EQ(decoded.type(), image.type());
  EXPECT_EQ(cv::norm(decoded, image, cv::NORM_INF), 0.0);  // PNG is lossless

  EXPECT_THROW(report.AddImage(cv::Mat(), "missing frame"), std::invalid_argument);
}

TEST_F(OutputTest, HtmlReportOpensWithTheOutcomeThenTheRunAndFoldsTheFullTable) {
  HtmlReport report("aperture sim: gap");
  report.AddSection("Path");
  const nlohmann::json summary = {{"command", "sim"},
                                  {"inputs", {{"scenario", "gap"}}},
                                  {"config", {{"gap", {{"roll_deg", 30}}}}},
                                  {"mission", {{"passed", true}}}};
  report.AddCollapsedTable(summary, "Every figure of summary.json");
  // Added last, shown first: the outcome is known at the end of a run.
  report.AddRunDescription(summary, 12.34);
  report.AddOutcome(
      {"passed", "gap mission: passed the gap", {{"position error at the gap", "1.0 cm", "4 cm"}}});
  const std::string html = report.ToHtml();
  const size_t outcome = html.find("<section class=\"outcome passed\"><h2>Outcome: passed</h2>");
  const size_t run = html.find("<h2>What was run</h2>");
  const size_t path = html.find("<h2>Path</h2>");
  const size_t full_table = html.find("<details><summary>Every figure of summary.json</summary>");
  ASSERT_NE(outcome, std::string::npos) << html;
  ASSERT_NE(full_table, std::string::npos) << html;
  EXPECT_LT(outcome, run);
  EXPECT_LT(run, path);
  EXPECT_LT(path, full_table);
  EXPECT_THAT(html, HasSubstr("<td>position error at the gap</td><td>1.0 cm</td><td>4 cm</td>"));
  EXPECT_THAT(html, HasSubstr("<th>command</th><td>aperture sim</td>"));
  EXPECT_THAT(html, HasSubstr("<th>wall time</th><td>12.3 s</td>"));
  EXPECT_THAT(html, HasSubstr("<details><summary>Configuration (every effective parameter)"
                              "</summary>\n<table><tr><th>gap.roll_deg</th>"));
  EXPECT_THAT(html.substr(full_table), HasSubstr("<th>mission.passed</th><td>true</td>"));

  report.AddOutcome({"failed", "replaced", {}});  // a second outcome replaces the first
  EXPECT_EQ(CountOccurrences(report.ToHtml(), "Outcome: "), 1);
  EXPECT_THAT(report.ToHtml(), HasSubstr("Outcome: failed"));
}

TEST_F(OutputTest, HtmlReportEmbedsJpegKeyFramesCloseToTheImage) {
  // A smooth frame with an edge, like a rendered view: JPEG at quality 85 stays within a few
  // grey levels on average (its 8x8 DCT quantization), at a fraction of the PNG's size.
  cv::Mat image(120, 160, CV_8UC3);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      image.at<cv::Vec3b>(y, x) = x < 80 ? cv::Vec3b(x, y, 100) : cv::Vec3b(200, 2 * y, x);
    }
  }
  HtmlReport jpeg_report("jpeg");
  jpeg_report.AddImage(image, "key frame", HtmlReport::ImageEncoding::kJpeg);
  HtmlReport png_report("png");
  png_report.AddImage(image, "key frame");
  const std::string html = jpeg_report.ToHtml();
  const cv::Mat decoded = DecodeFirstImage(html, "data:image/jpeg;base64,");
  ASSERT_EQ(decoded.size(), image.size());
  ASSERT_EQ(decoded.type(), image.type());
  EXPECT_LT(cv::norm(decoded, image, cv::NORM_L1) / image.total() / 3, 2.0);
  EXPECT_LT(html.size(), png_report.ToHtml().size());
  EXPECT_THROW(
      jpeg_report.AddImage(cv::Mat(8, 8, CV_8UC4), "alpha", HtmlReport::ImageEncoding::kJpeg),
      std::invalid_argument);
}

// ---- Progress bar
// --------------------------------------------------------------------------------

TEST_F(OutputTest, ProgressBarIsSilentWhenNotATerminal) {
  std::ostringstream sink;
  {
    ProgressBar bar("frames", 10, sink, false);
    for (int i = 1; i <= 10; ++i) bar.Update(i);
    bar.Finish();
  }
  EXPECT_TRUE(sink.str().empty());
}

TEST_F(OutputTest, DefaultProgressBarDetectsRedirectedStderr) {
  // CaptureStderr points fd 2 at a file, so isatty(2) is false whether or not the test itself
  // runs in a terminal.
  ::testing::internal::CaptureStderr();
  {
    ProgressBar bar("frames", 3);
    EXPECT_FALSE(bar.enabled());
    bar.Update(1);
    bar.Finish();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST_F(OutputTest, ProgressBarDrawsLabelCountsAndEndsTheLine) {
  std::ostringstream sink;
  ProgressBar bar("frames", 10, sink, true);
  bar.Update(3);  // the first update always draws
  EXPECT_THAT(sink.str(), HasSubstr("frames ["));
  EXPECT_THAT(sink.str(), HasSubstr(" 3/10 "));
  bar.Update(10);  // completion always draws, regardless of throttling
  EXPECT_THAT(sink.str(), HasSubstr(" 10/10 "));
  EXPECT_THAT(bar.Line(), HasSubstr("[########################]"));
  bar.Finish();
  EXPECT_EQ(sink.str().back(), '\n');
  const std::size_t length = sink.str().size();
  bar.Finish();  // idempotent
  EXPECT_EQ(sink.str().size(), length);
}

// ---- Video
// ---------------------------------------------------------------------------------------

class VideoWriterTest : public OutputTest, public ::testing::WithParamInterface<VideoFormat> {};

TEST_P(VideoWriterTest, WritesReadableFileAndRenamesIt) {
  fs::create_directories(directory_);
  const cv::Size size(64, 48);
  std::optional<std::string> written;
  std::string codec;
  {
    VideoWriter video((directory_ / "overlay").string(), 10.0, GetParam());
    for (int i = 0; i < 12; ++i) {
      video.Write(cv::Mat(size, CV_8UC3, cv::Scalar(20 * (i % 10), 100, 200)));
    }
    EXPECT_THROW(video.Write(cv::Mat(10, 10, CV_8UC3)), std::invalid_argument);
    written = video.Close();
    codec = video.codec();
  }
  ASSERT_TRUE(written.has_value());
  // On this platform (Debian 12, OpenCV 4.6 + FFmpeg) mp4v opens, so no fallback is taken.
  EXPECT_EQ(codec, GetParam() == VideoFormat::kAvi ? "MJPG" : "mp4v");
  EXPECT_EQ(fs::path(*written).extension(), codec == "MJPG" ? ".avi" : ".mp4");
  EXPECT_EQ(ListFiles(directory_),
            std::vector<std::string>{fs::path(*written).filename().string()});
  cv::VideoCapture capture(*written);
  ASSERT_TRUE(capture.isOpened());
  int frames = 0;
  cv::Mat frame;
  while (capture.read(frame)) {
    EXPECT_EQ(frame.size(), size);
    // Lossy codecs: a flat colour comes back within a few grey levels (20 is generous for both).
    EXPECT_NEAR(cv::mean(frame)[1], 100.0, 20.0);
    EXPECT_NEAR(cv::mean(frame)[0], 20.0 * (frames % 10), 20.0);
    ++frames;
  }
  EXPECT_EQ(frames, 12);
}

INSTANTIATE_TEST_SUITE_P(Formats, VideoWriterTest,
                         ::testing::Values(VideoFormat::kMp4OrAvi, VideoFormat::kAvi));

TEST_F(OutputTest, BackgroundVideoWriterEncodesEveryFrameInOrder) {
  fs::create_directories(directory_);
  const cv::Size size(64, 48);
  // More frames than the queue holds, so Write has to wait for the encoder at times.
  const int frame_count = 3 * static_cast<int>(BackgroundVideoWriter::kMaxQueuedFrames);
  std::optional<std::string> written;
  {
    BackgroundVideoWriter video((directory_ / "overlay").string(), 10.0, VideoFormat::kAvi);
    for (int i = 0; i < frame_count; ++i) {
      video.Write(cv::Mat(size, CV_8UC3, cv::Scalar(10 * i, 100, 200)));
    }
    written = video.Close();
    EXPECT_EQ(video.Close(), written);  // idempotent
    EXPECT_THROW(video.Write(cv::Mat(size, CV_8UC3)), std::logic_error);
  }
  ASSERT_TRUE(written.has_value());
  cv::VideoCapture capture(*written);
  ASSERT_TRUE(capture.isOpened());
  int frames = 0;
  cv::Mat frame;
  while (capture.read(frame)) {
    // MJPG: a flat colour comes back within a few levels; 10 levels apart tells the order.
    EXPECT_NEAR(cv::mean(frame)[0], 10.0 * frames, 4.0) << "frame " << frames;
    ++frames;
  }
  EXPECT_EQ(frames, frame_count);
}

TEST_F(OutputTest, BackgroundVideoWriterReportsEncoderErrors) {
  fs::create_directories(directory_);
  BackgroundVideoWriter video((directory_ / "bad").string(), 10.0, VideoFormat::kAvi);
  video.Write(cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(0)));
  video.Write(cv::Mat(10, 10, CV_8UC3, cv::Scalar::all(0)));  // size differs: the encoder fails
  EXPECT_THROW(video.Close(), std::invalid_argument);
}

TEST_F(OutputTest, VideoWriterWithoutFramesWritesNothing) {
  fs::create_directories(directory_);
  {
    VideoWriter unused((directory_ / "unused").string(), 30.0);
    EXPECT_FALSE(unused.Close().has_value());
  }
  EXPECT_TRUE(ListFiles(directory_).empty());
  EXPECT_THROW(VideoWriter("x", 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::output
