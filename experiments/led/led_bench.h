#pragma once
// `aperture bench led` (issue 6; Faessler thesis C.4 analogs): the LedTracker on sequences
// rendered by the simulator (LedTargetRenderer: 752 x 480 pinhole camera with 90 deg field of view
// like the thesis' mvBlueFOX, infrared mode with sensor noise and motion blur) against their
// ground truth. Sections, each under its own summary key:
//   accuracy   Table C.1 analog: 6-DOF excitation at 1.05-1.95 m, n_L = 4
//   sweep      Fig. C.7 analog: distances 0.3-5.6 m, n_L = 5 (box plots per distance); poses
//              > 90 deg off (wrong labellings) counted per distance as outliers, left out of the
//              box plots and medians
//   occlusion  C.4.2 / Fig. C.10 analog: one LED of five hidden mid-sequence; also a fresh start
//              (no prior pose) during the occlusion
//   merged     C.4.2 / Fig. C.11 analog: two LEDs sweep through alignment (merged blobs)
//   brute_force_timing  Table C.2 as the thesis timed it: brute force on the full image in every
//              frame (n_L = 4 and 5), mean, sigma and max per step beside the thesis' values
//   body_occlusion  issue 22: a held-out five-LED layout on a body that hides one or two LEDs in
//              about a third of the frames, 1.8-2.5 m; frames with a pose by visible LEDs, errors
//              by the LEDs a pose rests on, rotation accuracy at 2 m, blob centroid errors
//   timing     Table C.2 analog: medians per stage [s], from the tracker's LedStageTimes and a
//              brute-force pass on the sweep's detections (+ one false detection)
//   acceptance the issues' acceptance checks of the sections run, as booleans
// With calibration_errors the images are rendered with the intrinsics and LED positions off by
// BenchCalibrationError (summary key calibration_error) while the tracker keeps the nominal ones.
// Errors: positions in m, orientations in deg (angle of the angle-axis error, C.4.1).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/led/led_target_renderer.h"
#include "output/html_report.h"

namespace aperture::experiments {

struct LedBenchOptions {
  std::uint64_t seed = 1;  // random poses of the sweep and the sensor noise
  // Fewer frames with the same code paths (for tests and quick looks).
  bool quick = false;
  // Per-frame CSV (section, t_s, status, detections, visible_leds, p_CT_true_x/y/z,
  // position_error_m, orientation_error_deg, position_sigma_m, orientation_sigma_deg, rms_px;
  // sigmas: largest, at detection_sigma_px); empty = none.
  std::string frames_csv_path;
  // Section keys to run (LedBenchSectionKeys()); empty = all. Timing covers the sections run.
  std::vector<std::string> only;
  // Render every section with BenchCalibrationError(seed) while the tracker keeps the nominal
  // camera and LED positions (issue 21).
  bool calibration_errors = false;
};

// The calibration-level errors of `--calibration-errors`: focal lengths +0.5 % (1.9 px of 376),
// principal point off by (+1.5, -1.0) px, every LED 1 mm off in a direction drawn from `seed`.
LedCalibrationError BenchCalibrationError(std::uint64_t seed);

// The section keys in the order they run.
std::vector<std::string> LedBenchSectionKeys();

// The sections to run: options.only in LedBenchSectionKeys() order, or all when empty.
// std::invalid_argument naming an unknown key.
std::vector<std::string> SelectedLedBenchSections(const LedBenchOptions& options);

// Runs section `key` on its own (each section has its own target, seeds and frame indices, so it
// tracks the same frames whatever else runs): its record {"section", "summary" (its figures
// under its key), "report" (its blocks), "frames" (its frames.csv rows), "stage_times" (samples
// for the timing section), "wall_time_s"} (experiments/bench/section_record.h).
// std::invalid_argument for an unknown key.
nlohmann::json RunLedBenchSection(const std::string& key, const LedBenchOptions& options);

// The bench's outputs from the records of the sections run, in LedBenchSectionKeys() order: every
// section's figures into *summary and blocks into *report, then timing (over the sections' stage
// times) and acceptance; frames.csv to options.frames_csv_path when set.
void WriteLedBenchOutputs(const LedBenchOptions& options,
                          const std::vector<nlohmann::json>& section_records,
                          nlohmann::json* summary, output::HtmlReport* report);

}  // namespace aperture::experiments
