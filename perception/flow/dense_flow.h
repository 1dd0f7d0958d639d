#pragma once
// DenseFlow: one interface over OpenCV's dense optical-flow methods, chosen by name so a front end
// can be configured with `--set ts2p.flow.method=dis_medium`.
//
//   method           library / paper                                   notes
//   dis_ultrafast    cv::DISOpticalFlow PRESET_ULTRAFAST (Kroeger 2016)  seed 002 Table II "DIS"
//   dis_fast         cv::DISOpticalFlow PRESET_FAST
//   dis_medium       cv::DISOpticalFlow PRESET_MEDIUM
//   farneback        cv::FarnebackOpticalFlow (polynomial expansion)
//   deepflow         cv::optflow DeepFlow (contrib)                      slow (~1 s at 576x384)
//   dual_tvl1        cv::optflow DualTVL1 (contrib)                      slow
//   rlof             cv::optflow dense RLOF (contrib; fed BGR)
//   pca_flow         cv::optflow PCAFlow (contrib)
//   sparse_to_dense  cv::optflow SparseToDense (contrib: PyrLK + interpolation)
// With `variational_refinement` the method's result seeds cv::VariationalRefinement (the
// energy-minimisation stage of DIS, Kroeger 2016 Sec. 2.3, run at full resolution).
//
// Contract: Compute(from, to) takes two images of the same size (CV_8UC1 gray or CV_8UC3 BGR;
// converted as each method needs) and returns CV_32FC2 flow [px] with from(x) ~ to(x + flow(x)).
// Throws std::invalid_argument for empty, differently sized or non-8-bit images; unknown method
// names throw from the constructor, listing the known ones.
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "config/param_reader.h"

namespace cv {
class DenseOpticalFlow;
}

namespace aperture::perception {

struct DenseFlowParams {
  // DIS-medium: the fastest method whose TS²P detection meets seed 002's FlowNet2 figures here
  // (docs/results/ts2p.md); dis_fast/dis_ultrafast trade edge accuracy for speed.
  std::string method = "dis_medium";
  // DIS methods only: iterations of DIS's own variational refinement at each scale (Kroeger 2016
  // Sec. 2.3); -1 keeps the preset's (ultrafast 0, fast and medium 5). It is most of DIS-medium's
  // cost at the finest scale.
  int dis_refinement_iterations = -1;
  bool variational_refinement = false;
  // cv::VariationalRefinement settings (OpenCV's defaults; used when variational_refinement).
  int refinement_fixed_point_iterations = 5;
  int refinement_sor_iterations = 5;

  void Validate() const;  // std::invalid_argument naming the field and the fix
};

void LoadParams(config::ParamReader& reader, DenseFlowParams* params);

// The names accepted as DenseFlowParams::method, in the table's order.
const std::vector<std::string>& DenseFlowMethodNames();

class DenseFlow {
 public:
  explicit DenseFlow(const DenseFlowParams& params);
  ~DenseFlow();
  DenseFlow(DenseFlow&&) noexcept;
  DenseFlow& operator=(DenseFlow&&) noexcept;

  // Flow from `from` to `to` (CV_32FC2, px). Not thread-safe (methods keep buffers).
  cv::Mat Compute(const cv::Mat& from, const cv::Mat& to);

  const DenseFlowParams& params() const { return params_; }
  // e.g. "dis_medium" or "dis_medium+variational".
  std::string Describe() const;

 private:
  DenseFlowParams params_;
  cv::Ptr<cv::DenseOpticalFlow> method_;
  cv::Ptr<cv::DenseOpticalFlow> refinement_;  // null unless variational_refinement
  bool needs_color_ = false;                  // RLOF takes CV_8UC3
};

}  // namespace aperture::perception
