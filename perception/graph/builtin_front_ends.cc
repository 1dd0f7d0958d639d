#include "perception/graph/builtin_front_ends.h"

#include "perception/gap/gap_node.h"
#include "perception/led/led_tracker_node.h"
#include "perception/mono_depth/mono_depth_node.h"
#include "perception/quality/image_quality_node.h"
#include "perception/tags/april_tag_node.h"
#include "perception/ts2p/gap_tracker_node.h"
#include "perception/ts2p/ts2p_node.h"

namespace aperture::perception {

void RegisterBuiltinFrontEnds(FrontEndRegistry& registry) {
  registry.Register(AprilTagNode::kName,
                    "AprilTag poses T_CT per tag with covariance and flip resolution, tags.csv, "
                    "optional tag map (seed 001 paper D); needs --calib and apriltag.size_m",
                    &AprilTagNode::Create);
  registry.Register(GapNode::kName,
                    "patterned gap detector (seed 000): pose T_GC with covariance; needs --calib",
                    &GapNode::Create);
  registry.Register(ImageQualityNode::kName,
                    "exposure histogram, mean intensity, over/under exposure, Laplacian sharpness",
                    &ImageQualityNode::Create);
  registry.Register(LedTrackerNode::kName,
                    "infrared-LED target pose T_CT with covariance (needs --calib; led.config)",
                    &LedTrackerNode::Create);
  registry.Register(MonoDepthNode::kName,
                    "monocular depth map per colour frame (seed 003 patch SVM; needs --color); "
                    "Table I errors when depth/ is beside the images",
                    &MonoDepthNode::Create);
  registry.Register(Ts2pNode::kName,
                    "TS2P unknown-gap detection from stacked flow parallax (seed 002): "
                    "openings/<index>.png, ts2p.csv",
                    &Ts2pNode::Create);
  registry.Register(GapTrackerNode::kName,
                    "KLT label tracking of the ts2p opening under FOE constraints (seed 002 "
                    "Alg. 1): safe point x_s, FOE, divergence; needs ts2p",
                    &GapTrackerNode::Create);
}

}  // namespace aperture::perception
