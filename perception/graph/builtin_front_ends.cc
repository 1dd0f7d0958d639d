#include "perception/graph/builtin_front_ends.h"

#include "perception/quality/image_quality_node.h"

namespace aperture::perception {

void RegisterBuiltinFrontEnds(FrontEndRegistry& registry) {
  registry.Register(ImageQualityNode::kName,
                    "exposure histogram, mean intensity, over/under exposure, Laplacian sharpness",
                    &ImageQualityNode::Create);
}

}  // namespace aperture::perception
