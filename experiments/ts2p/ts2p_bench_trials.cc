#include "experiments/ts2p/ts2p_bench_trials.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <utility>

#include "perception/ts2p/label_tracker.h"

namespace aperture::experiments {
namespace {

constexpr double kPaperBackgroundDepthM = 5.7;
// Depth-sweep scans are trials of their own (index offset) so that the Z_F sweep does not repeat
// Table II's scenes.
constexpr int kDepthTrialOffset = 100000;

enum class UnitKind { kSweepDetection, kDetection, kDepth, kTracking };

struct Unit {
  UnitKind kind;
  int index;  // detection: the trial; depth: depth-major scan; tracking: the trial
};

const char* KindName(UnitKind kind) {
  switch (kind) {
    case UnitKind::kSweepDetection:
    case UnitKind::kDetection:
      return "detection";
    case UnitKind::kDepth:
      return "depth";
    case UnitKind::kTracking:
      return "tracking";
  }
  return "";
}

// The four sequences interleaved evenly: element j of a sequence of c elements sits at
// (j + 1/2) / c of the run (ties: in the sequences' order). Exact integer comparisons.
std::vector<Unit> Schedule(const Ts2pBenchOptions& options) {
  const int sweep = std::min(options.sweep_trials, options.trials);
  struct Sequence {
    UnitKind kind;
    int first, count;
  };
  const Sequence sequences[] = {
      {UnitKind::kSweepDetection, 0, sweep},
      {UnitKind::kDetection, sweep, options.trials - sweep},
      {UnitKind::kDepth, 0,
       static_cast<int>(options.foreground_depths_m.size()) * options.depth_trials},
      {UnitKind::kTracking, 0, options.tracking_trials}};
  struct Entry {
    Unit unit;
    std::int64_t j, count;
  };
  std::vector<Entry> entries;
  for (const Sequence& s : sequences) {
    for (int j = 0; j < s.count; ++j) entries.push_back({{s.kind, s.first + j}, j, s.count});
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return (2 * a.j + 1) * b.count < (2 * b.j + 1) * a.count;
  });
  std::vector<Unit> units;
  units.reserve(entries.size());
  for (const Entry& e : entries) units.push_back(e.unit);
  return units;
}

// Restores OpenCV's thread count on scope exit.
class SingleThreadedOpenCv {
 public:
  SingleThreadedOpenCv() : previous_(cv::getNumThreads()) { cv::setNumThreads(1); }
  ~SingleThreadedOpenCv() { cv::setNumThreads(previous_); }
  SingleThreadedOpenCv(const SingleThreadedOpenCv&) = delete;
  SingleThreadedOpenCv& operator=(const SingleThreadedOpenCv&) = delete;

 private:
  int previous_;
};

// The frames of an N-stack from a scan rendered with a larger even stack (offsets -M/2..M/2
// without 0, in order): those within +-N/2 of the reference.
std::vector<cv::Mat> SubStack(const Ts2pScan& scan, int rendered_stack, int stack) {
  std::vector<cv::Mat> frames;
  const int half = rendered_stack / 2;
  for (int k = 0, i = 0; k <= rendered_stack; ++k) {
    if (k == half) continue;
    if (std::abs(k - half) <= stack / 2) frames.push_back(scan.frames[i]);
    ++i;
  }
  return frames;
}

cv::Mat Resized(const cv::Mat& image, cv::Size size) {
  cv::Mat out;
  cv::resize(image, out, size, 0, 0, cv::INTER_AREA);
  return out;
}

// Seed 002 Fig. 10 colours on the reference image.
cv::Mat Overlay(const cv::Mat& reference, const cv::Mat& opening, const cv::Mat& truth) {
  cv::Mat bgr;
  cv::cvtColor(reference, bgr, cv::COLOR_GRAY2BGR);
  cv::Mat tint(bgr.size(), CV_8UC3, cv::Scalar(0, 0, 0));
  tint.setTo(cv::Scalar(0, 200, 0), opening & truth);
  tint.setTo(cv::Scalar(0, 220, 255), ~opening & truth);
  tint.setTo(cv::Scalar(0, 0, 255), opening & ~truth);
  cv::addWeighted(bgr, 0.55, tint, 0.45, 0.0, bgr);
  return bgr;
}

nlohmann::json TimingToJson(const perception::Ts2pTiming& t) {
  return {{"flow_ms", t.flow_ms},
          {"derotation_ms", t.derotation_ms},
          {"stacking_ms", t.stacking_ms},
          {"edge_aware_ms", t.edge_aware_ms},
          {"segmentation_ms", t.segmentation_ms},
          {"safe_point_ms", t.safe_point_ms},
          {"total_ms", t.total_ms},
          {"cpu_ms", t.cpu_ms}};
}

perception::Ts2pTiming TimingFromJson(const nlohmann::json& json) {
  perception::Ts2pTiming t;
  t.flow_ms = json.at("flow_ms").get<double>();
  t.derotation_ms = json.at("derotation_ms").get<double>();
  t.stacking_ms = json.at("stacking_ms").get<double>();
  t.edge_aware_ms = json.at("edge_aware_ms").get<double>();
  t.segmentation_ms = json.at("segmentation_ms").get<double>();
  t.safe_point_ms = json.at("safe_point_ms").get<double>();
  t.total_ms = json.at("total_ms").get<double>();
  t.cpu_ms = json.at("cpu_ms").get<double>();
  return t;
}

// One detection on `frames`, scored against `truth`, as an outcome of series (group, name, x).
nlohmann::json Evaluate(perception::Ts2pDetector& detector, const cv::Mat& reference,
                        const std::vector<cv::Mat>& frames, const cv::Mat& truth,
                        const Ts2pScanConfig& config, int trial, const std::string& group,
                        const std::string& series, double x,
                        perception::Ts2pDetection* detection_out = nullptr) {
  perception::Ts2pDetection detection = detector.Detect(reference, frames);
  const perception::OpeningScore score = perception::ScoreOpening(detection.opening, truth);
  nlohmann::json outcome = {{"group", group},
                            {"series", series},
                            {"x", x},
                            {"trial", trial},
                            {"shape", config.shape},
                            {"valid", detection.valid},
                            {"overlap", score.overlap},
                            {"false_negative", score.false_negative},
                            {"false_positive", score.false_positive},
                            {"timing", TimingToJson(detection.timing)}};
  if (detection_out) *detection_out = std::move(detection);
  return outcome;
}

Ts2pTrialOutcome OutcomeFromJson(const nlohmann::json& json) {
  Ts2pTrialOutcome o;
  o.trial = json.at("trial").get<int>();
  o.shape = json.at("shape").get<std::string>();
  o.valid = json.at("valid").get<bool>();
  o.score.overlap = json.at("overlap").get<double>();
  o.score.false_negative = json.at("false_negative").get<double>();
  o.score.false_positive = json.at("false_positive").get<double>();
  o.timing = TimingFromJson(json.at("timing"));
  return o;
}

nlohmann::json TrackingToJson(const Ts2pTrackingRun& run) {
  return {{"trial", run.trial},
          {"drift_px", run.drift_px},
          {"filtered_drift_px", run.filtered_drift_px},
          {"propagation_ms", run.propagation_ms},
          {"klt_ms", run.klt_ms},
          {"resets", run.resets}};
}

Ts2pTrackingRun TrackingFromJson(const nlohmann::json& json) {
  Ts2pTrackingRun run;
  run.trial = json.at("trial").get<int>();
  run.drift_px = json.at("drift_px").get<std::vector<double>>();
  run.filtered_drift_px = json.at("filtered_drift_px").get<std::vector<double>>();
  run.propagation_ms = json.at("propagation_ms").get<std::vector<double>>();
  run.klt_ms = json.at("klt_ms").get<std::vector<double>>();
  run.resets = json.at("resets").get<int>();
  return run;
}

Ts2pSeries& SeriesNamed(std::vector<Ts2pSeries>& series, const std::string& name, double x) {
  for (Ts2pSeries& s : series) {
    if (s.name == name) return s;
  }
  series.push_back({name, x, {}});
  return series.back();
}

std::vector<Ts2pSeries>* SeriesGroup(Ts2pBenchResult* result, const std::string& group) {
  if (group == "methods") return &result->methods;
  if (group == "stacks") return &result->stacks;
  if (group == "sizes") return &result->sizes;
  if (group == "depths") return &result->depths;
  throw std::invalid_argument("bench ts2p record: unknown series group '" + group + "'");
}

}  // namespace

int Ts2pBenchTrialCount(const Ts2pBenchOptions& options) {
  return options.trials +
         static_cast<int>(options.foreground_depths_m.size()) * options.depth_trials +
         options.tracking_trials;
}

struct Ts2pBenchTrials::State {
  explicit State(const Ts2pBenchOptions& o)
      : options(o), units(Schedule(o)), sweep_detector(o.detector) {
    for (const std::string& method : o.methods) {
      perception::Ts2pParams params = o.detector;
      params.flow.method = method;
      method_detectors.emplace_back(params);
    }
  }

  nlohmann::json Detection(int trial, bool sweep);
  nlohmann::json Depth(int scan);
  nlohmann::json Tracking(int trial);

  const SingleThreadedOpenCv single_threaded;
  Ts2pBenchOptions options;
  std::vector<Unit> units;
  std::vector<perception::Ts2pDetector> method_detectors;
  perception::Ts2pDetector sweep_detector;
  sim::RayCaster caster;
};

nlohmann::json Ts2pBenchTrials::State::Detection(int trial, bool sweep) {
  Ts2pScanConfig config = DrawTs2pTrial(options.ranges, options.seed, trial);
  const int max_stack = *std::max_element(options.stacks.begin(), options.stacks.end());
  const int rendered = sweep ? std::max(max_stack, 4) : 4;
  config.stack = rendered;
  const Ts2pScan scan = RenderTs2pScan(config, caster);
  const std::vector<cv::Mat> stack4 = SubStack(scan, rendered, 4);
  nlohmann::json outcomes = nlohmann::json::array();
  nlohmann::json examples = nlohmann::json::array();
  for (std::size_t m = 0; m < options.methods.size(); ++m) {
    outcomes.push_back(Evaluate(method_detectors[m], scan.reference, stack4, scan.truth, config,
                                trial, "methods", options.methods[m], 0.0));
  }
  if (sweep) {
    for (int stack : options.stacks) {
      perception::Ts2pDetection detection;
      outcomes.push_back(Evaluate(sweep_detector, scan.reference, SubStack(scan, rendered, stack),
                                  scan.truth, config, trial, "stacks", "N=" + std::to_string(stack),
                                  stack, &detection));
      const bool first_of_shape = trial < static_cast<int>(kTs2pShapes.size());
      if (stack == 4 && first_of_shape) {
        std::vector<std::uint8_t> png;
        cv::imencode(".png", Overlay(scan.reference, detection.opening, scan.truth), png);
        examples.push_back(
            {{"shape", config.shape}, {"png", nlohmann::json::binary(std::move(png))}});
      }
    }
    for (int width : options.widths) {
      const cv::Size size(width, width * 2 / 3);
      std::vector<cv::Mat> frames;
      for (const cv::Mat& frame : stack4) frames.push_back(Resized(frame, size));
      const cv::Mat truth = Resized(scan.truth, size) >= 128;
      if (cv::countNonZero(truth) == 0) continue;
      outcomes.push_back(
          Evaluate(sweep_detector, Resized(scan.reference, size), frames, truth, config, trial,
                   "sizes", std::to_string(size.width) + "x" + std::to_string(size.height), width));
    }
  }
  return {{"outcomes", outcomes}, {"examples", examples}};
}

nlohmann::json Ts2pBenchTrials::State::Depth(int scan_index) {
  const double depth =
      options.foreground_depths_m.at(static_cast<std::size_t>(scan_index / options.depth_trials));
  const int trial = kDepthTrialOffset + scan_index % options.depth_trials;
  Ts2pScanConfig config = DrawTs2pTrial(options.ranges, options.seed, trial);
  config.foreground_depth_m = depth;
  config.background_depth_m = kPaperBackgroundDepthM;
  const Ts2pScan scan = RenderTs2pScan(config, caster);
  char name[32];
  std::snprintf(name, sizeof(name), "Z_F=%.2f", depth);
  return {{"outcomes",
           nlohmann::json::array({Evaluate(sweep_detector, scan.reference, scan.frames, scan.truth,
                                           config, trial, "depths", name, depth)})},
          {"examples", nlohmann::json::array()}};
}

nlohmann::json Ts2pBenchTrials::State::Tracking(int trial) {
  const Ts2pScanConfig config = DrawTs2pTrial(options.ranges, options.seed, trial);
  Ts2pTrackingRun run;
  run.trial = trial;
  const Ts2pScan scan = RenderTs2pScan(config, caster);
  const perception::Ts2pDetection detection = sweep_detector.Detect(scan.reference, scan.frames);
  if (detection.valid) {
    const Ts2pApproach approach =
        RenderTs2pApproach(config, options.tracking_frames, options.tracking_speed_mps, caster);
    perception::LabelTracker tracker(options.tracker);
    tracker.Initialize(scan.reference, detection.opening, detection.safe_point_px,
                       detection.contour, 0.0, 0);
    const Eigen::Vector2d e0 =
        detection.safe_point_px - perception::GeometricMedian(scan.truth, 30);
    for (std::size_t k = 0; k < approach.frames.size(); ++k) {
      const perception::OpeningTrack track = tracker.Track(
          approach.frames[k], (k + 1) / approach.frame_rate_hz, static_cast<int>(k + 1));
      const Eigen::Vector2d truth = perception::GeometricMedian(approach.truth[k], 30);
      run.drift_px.push_back((track.safe_point_measured_px - truth - e0).norm());
      run.filtered_drift_px.push_back((track.safe_point_px - truth - e0).norm());
      run.propagation_ms.push_back(track.propagation_ms);
      run.klt_ms.push_back(track.klt_ms);
      run.resets += track.foreground_reset + track.background_reset;
    }
  }
  return {{"outcomes", nlohmann::json::array()},
          {"examples", nlohmann::json::array()},
          {"tracking", TrackingToJson(run)}};
}

Ts2pBenchTrials::Ts2pBenchTrials(const Ts2pBenchOptions& options) {
  options.Validate();
  state_ = std::make_unique<State>(options);
}

Ts2pBenchTrials::~Ts2pBenchTrials() = default;

nlohmann::json Ts2pBenchTrials::Run(int unit) {
  if (unit < 0 || unit >= static_cast<int>(state_->units.size())) {
    throw std::out_of_range("bench ts2p: unit " + std::to_string(unit) + " of " +
                            std::to_string(state_->units.size()));
  }
  const Unit& u = state_->units[static_cast<std::size_t>(unit)];
  nlohmann::json record;
  switch (u.kind) {
    case UnitKind::kSweepDetection:
      record = state_->Detection(u.index, true);
      break;
    case UnitKind::kDetection:
      record = state_->Detection(u.index, false);
      break;
    case UnitKind::kDepth:
      record = state_->Depth(u.index);
      break;
    case UnitKind::kTracking:
      record = state_->Tracking(u.index);
      break;
  }
  record["kind"] = KindName(u.kind);
  record["index"] = u.index;
  return record;
}

Ts2pBenchResult Ts2pBenchResultFromRecords(const Ts2pBenchOptions& options,
                                           const std::vector<nlohmann::json>& records) {
  const std::vector<Unit> units = Schedule(options);
  if (records.size() != units.size()) {
    throw std::invalid_argument("bench ts2p: " + std::to_string(records.size()) +
                                " records for a run of " + std::to_string(units.size()) + " units");
  }
  Ts2pBenchResult result;
  result.options = options;
  // Per kind, the units' own order: the order in which a sequential run meets the series.
  std::vector<std::vector<const nlohmann::json*>> by_kind(4);
  for (std::size_t k = 0; k < units.size(); ++k) {
    const nlohmann::json& record = records[k];
    if (record.value("kind", "") != KindName(units[k].kind) ||
        record.value("index", -1) != units[k].index) {
      throw std::invalid_argument(
          "bench ts2p: record " + std::to_string(k) + " is " + record.value("kind", "?") + " " +
          std::to_string(record.value("index", -1)) + ", the run has " + KindName(units[k].kind) +
          " " + std::to_string(units[k].index) + " there");
    }
    by_kind[static_cast<std::size_t>(units[k].kind)].push_back(&record);
  }
  std::vector<const nlohmann::json*> ordered;
  for (const auto& kind : by_kind) ordered.insert(ordered.end(), kind.begin(), kind.end());
  try {
    for (const nlohmann::json* record : ordered) {
      for (const nlohmann::json& outcome : record->at("outcomes")) {
        SeriesNamed(*SeriesGroup(&result, outcome.at("group").get<std::string>()),
                    outcome.at("series").get<std::string>(), outcome.at("x").get<double>())
            .outcomes.push_back(OutcomeFromJson(outcome));
      }
      for (const nlohmann::json& example : record->at("examples")) {
        const std::vector<std::uint8_t>& png = example.at("png").get_binary();
        result.examples.emplace_back(example.at("shape").get<std::string>(),
                                     cv::imdecode(png, cv::IMREAD_COLOR));
      }
      if (record->contains("tracking")) {
        result.tracking.push_back(TrackingFromJson(record->at("tracking")));
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("bench ts2p record: ") + e.what());
  }
  return result;
}

}  // namespace aperture::experiments
