#include "perception/flow/dense_flow.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <opencv2/optflow.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

namespace aperture::perception {
namespace {

std::string KnownMethods() {
  std::string known;
  for (const std::string& name : DenseFlowMethodNames())
    known += (known.empty() ? "" : ", ") + name;
  return known;
}

cv::Ptr<cv::DenseOpticalFlow> MakeMethod(const std::string& method) {
  if (method == "dis_ultrafast")
    return cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_ULTRAFAST);
  if (method == "dis_fast") return cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_FAST);
  if (method == "dis_medium") return cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_MEDIUM);
  if (method == "farneback") return cv::FarnebackOpticalFlow::create();
  if (method == "deepflow") return cv::optflow::createOptFlow_DeepFlow();
  if (method == "dual_tvl1") return cv::optflow::createOptFlow_DualTVL1();
  if (method == "rlof") return cv::optflow::createOptFlow_DenseRLOF();
  if (method == "pca_flow") return cv::optflow::createOptFlow_PCAFlow();
  if (method == "sparse_to_dense") return cv::optflow::createOptFlow_SparseToDense();
  throw std::invalid_argument("unknown dense flow method '" + method +
                              "' (known: " + KnownMethods() + ")");
}

cv::Mat ToChannels(const cv::Mat& image, int channels) {
  if (image.channels() == channels) return image;
  cv::Mat converted;
  cv::cvtColor(image, converted, channels == 1 ? cv::COLOR_BGR2GRAY : cv::COLOR_GRAY2BGR);
  return converted;
}

}  // namespace

void DenseFlowParams::Validate() const {
  const auto& names = DenseFlowMethodNames();
  if (std::find(names.begin(), names.end(), method) == names.end()) {
    throw std::invalid_argument("flow.method '" + method + "' is unknown; use one of " +
                                KnownMethods());
  }
  if (dis_refinement_iterations < -1) {
    throw std::invalid_argument(
        "flow.dis_refinement_iterations must be >= 0 or -1 (the preset's), "
        "got " +
        std::to_string(dis_refinement_iterations));
  }
  if (refinement_fixed_point_iterations < 1 || refinement_sor_iterations < 1) {
    throw std::invalid_argument(
        "flow.refinement_fixed_point_iterations and refinement_sor_iterations must be >= 1");
  }
}

void LoadParams(config::ParamReader& reader, DenseFlowParams* params) {
  reader.Read("method", &params->method);
  reader.Read("dis_refinement_iterations", &params->dis_refinement_iterations);
  reader.Read("variational_refinement", &params->variational_refinement);
  reader.Read("refinement_fixed_point_iterations", &params->refinement_fixed_point_iterations);
  reader.Read("refinement_sor_iterations", &params->refinement_sor_iterations);
  reader.Validate(*params);
}

const std::vector<std::string>& DenseFlowMethodNames() {
  static const std::vector<std::string> names{"dis_ultrafast", "dis_fast", "dis_medium",
                                              "farneback",     "deepflow", "dual_tvl1",
                                              "rlof",          "pca_flow", "sparse_to_dense"};
  return names;
}

DenseFlow::DenseFlow(const DenseFlowParams& params) : params_(params) {
  params_.Validate();
  method_ = MakeMethod(params_.method);
  if (auto dis = method_.dynamicCast<cv::DISOpticalFlow>();
      dis && params_.dis_refinement_iterations >= 0) {
    dis->setVariationalRefinementIterations(params_.dis_refinement_iterations);
  }
  needs_color_ = params_.method == "rlof";
  if (params_.variational_refinement) {
    cv::Ptr<cv::VariationalRefinement> refinement = cv::VariationalRefinement::create();
    refinement->setFixedPointIterations(params_.refinement_fixed_point_iterations);
    refinement->setSorIterations(params_.refinement_sor_iterations);
    refinement_ = refinement;
  }
}

DenseFlow::~DenseFlow() = default;
DenseFlow::DenseFlow(DenseFlow&&) noexcept = default;
DenseFlow& DenseFlow::operator=(DenseFlow&&) noexcept = default;

std::string DenseFlow::Describe() const {
  const bool dis_override =
      params_.dis_refinement_iterations >= 0 && params_.method.rfind("dis_", 0) == 0;
  return params_.method +
         (dis_override ? "/refine" + std::to_string(params_.dis_refinement_iterations) : "") +
         (params_.variational_refinement ? "+variational" : "");
}

cv::Mat DenseFlow::Compute(const cv::Mat& from, const cv::Mat& to) {
  if (from.empty() || to.empty() || from.size() != to.size() || from.depth() != CV_8U ||
      to.depth() != CV_8U || from.channels() != to.channels() ||
      (from.channels() != 1 && from.channels() != 3)) {
    throw std::invalid_argument(
        "DenseFlow::Compute needs two non-empty 8-bit images of one size and channel count "
        "(gray or BGR); got " +
        std::to_string(from.cols) + "x" + std::to_string(from.rows) + " and " +
        std::to_string(to.cols) + "x" + std::to_string(to.rows));
  }
  const int channels = needs_color_ ? 3 : 1;
  const cv::Mat from_in = ToChannels(from, channels);
  const cv::Mat to_in = ToChannels(to, channels);
  cv::Mat flow;
  method_->calc(from_in, to_in, flow);
  if (refinement_) {
    // VariationalRefinement refines the flow it is given (gray input only).
    refinement_->calc(ToChannels(from, 1), ToChannels(to, 1), flow);
  }
  return flow;
}

}  // namespace aperture::perception
