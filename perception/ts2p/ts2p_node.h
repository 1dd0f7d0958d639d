#pragma once
// Front end "ts2p": TS²P gap detection (Ts2pDetector, seed 002 Sec. II) on an image sequence.
// Keeps the last stack * stride + 1 frames; every `interval` frames (0: stack * stride, i.e.
// non-overlapping stacks) it detects with the middle frame of that window as the reference and
// the frames every `stride` frames before and after it as the stack, so a detection is reported
// stack / 2 * stride frames after its reference frame, in the reference frame's pixels and under
// the reference frame's index and time. Gyro derotation (Ts2pDetector step 2) when the frames
// carry IMU samples (Frame::imu, e.g. a bag's --imu-topic) and `gyro_derotation` is on: the rates
// are integrated (GyroIntegrator) and each stack frame's R_CkCr = R_CB R_BkBr R_BC comes through
// the calibration's T_BC; a source with IMU but no calibration is an error naming both fixes.
// Frames before the first IMU sample, and sequences without one, are stacked as they are.
//   reads:   "frame" (Frame)
//   writes:  "ts2p" (Ts2pOutput: the latest detection, whether it is new this frame)
//   metrics: detected (1 when a new opening was reported this frame, 0 when a detection found
//            none, NaN between detections), area_px, safe_u_px, safe_v_px, reference_index,
//            total_ms, derotated (1 when the detection used gyro rotations) (NaN unless a
//            detection ran this frame).
//   files:   (with FrontEndResources::output_directory) openings/<reference index>.png (8-bit,
//            255 = O), ts2p.csv (t_s, index, valid, area_px, safe_u_px, safe_v_px, stack, flow,
//            derotated, time per stage [ms]) — one row per detection.
//   overlay: the latest contour C (green) and safe point x_s (red cross).
// Parameters (section `ts2p`): stack, stride, interval, gyro_derotation, and the Ts2pParams
// fields (flow.method, segmentation, ...).
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "output/csv_writer.h"
#include "perception/camera/calibration_io.h"
#include "perception/estimation/gyro_integrator.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/node.h"
#include "perception/ts2p/ts2p_detector.h"

namespace aperture::perception {

struct Ts2pNodeParams {
  Ts2pParams detector;
  int stack = 4;     // N (paper N = 4; 2 and 8 in Fig. 13); even, so the reference is mid-stack
  int stride = 2;    // frames between stacked images: at 30 Hz and ~1 m/s, ~7 cm baselines
  int interval = 0;  // frames between detections; 0 = stack * stride
  bool gyro_derotation = true;  // derotate with the frames' IMU samples when they carry any

  void Validate() const;
};

void LoadParams(config::ParamReader& reader, Ts2pNodeParams* params);

// The "ts2p" slot.
struct Ts2pOutput {
  std::shared_ptr<const Ts2pDetection> detection;  // latest (valid or not); null before the first
  bool fresh = false;                              // detection ran on this frame
  int reference_index = -1;  // Frame::index of the detection's reference frame
  double reference_t_s = 0.0;
  bool derotated = false;   // the detection used gyro rotations
  cv::Mat reference_image;  // gray reference frame (the tracker starts from it)
};

class Ts2pNode final : public Node {
 public:
  static constexpr const char* kName = "ts2p";
  static constexpr const char* kOutputSlot = "ts2p";

  // `calibration` (optional) gives the camera model and T_BC that gyro derotation needs.
  Ts2pNode(const Ts2pNodeParams& params, const std::string& output_dir,
           const std::optional<CameraCalibration>& calibration = std::nullopt);

  static std::unique_ptr<Node> Create(config::ParamReader& params,
                                      const FrontEndResources& resources);

  std::string Name() const override { return kName; }
  std::vector<SlotSpec> Inputs() const override;
  std::vector<SlotSpec> Outputs() const override;
  void Run(NodeContext& context) override;
  std::map<std::string, double> Metrics(const NodeContext& context) const override;
  void DrawOverlay(const NodeContext& context, cv::Mat& bgr) const override;

 private:
  struct Buffered {
    int index;
    double t_s;
    cv::Mat gray;
    std::optional<Eigen::Matrix3d> R_B0B;  // integrated gyro orientation at t_s, if any
  };
  void Write(const Ts2pOutput& output);
  // One R_CkCr per stack frame from the window's gyro orientations; empty (no derotation) unless
  // every frame of the window has one.
  std::vector<Eigen::Matrix3d> StackRotations(std::size_t reference) const;

  Ts2pNodeParams params_;
  std::optional<CameraCalibration> calibration_;
  Ts2pDetector detector_;
  GyroIntegrator gyro_;
  std::string output_dir_;
  std::unique_ptr<output::CsvWriter> csv_;
  std::deque<Buffered> window_;
  int frames_since_detection_ = 0;
  Ts2pOutput latest_;
};

}  // namespace aperture::perception
