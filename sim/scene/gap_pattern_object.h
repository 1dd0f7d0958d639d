#pragma once
// The patterned gap of seed 000 (Falanga et al. 2017) as a scene object: a white panel with the
// black band between GapPattern::outer_size_m and inner_size_m, the white band down to
// opening_size_m and the opening cut out as a hole (perception/gap/gap_pattern.h describes the
// pattern). The object frame O is the detector's gap frame G (centre of the opening, x along the
// long side, y down when seen along +z), so ground truth is T_CG = T_WC^-1 * T_WO.
// The texture has 1 cm nearest-filtered texels; every pattern edge lies on a texel border when
// the sizes and the panel margins are multiples of 2 cm.
#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "perception/camera/camera_model.h"
#include "perception/gap/gap_pattern.h"
#include "sim/scene/scene.h"

namespace aperture::sim {

// panel_size_m: the whole panel (white margin around the outer rectangle) [m]. Throws
// std::invalid_argument naming the field when the panel does not contain the outer rectangle or
// the pattern is invalid (perception::GapPattern::ValidatePattern).
SceneObject MakeGapPatternObject(const perception::GapPattern& pattern,
                                 const Eigen::Vector2d& panel_size_m, const Eigen::Isometry3d& T_WG,
                                 const std::string& name = "gap");

// True when the whole pattern shows in a rendered frame: each outer corner pushed 5 % outwards
// (a margin of the white surround) projects in front of the camera, 3 px inside the image, onto
// a pixel where the renderer saw the gap object (object_id: RenderOutput::object_id, CV_32SC1).
bool GapPatternInView(const perception::CameraModel& camera, const perception::GapPattern& pattern,
                      const Eigen::Isometry3d& T_CG, const cv::Mat& object_id, int gap_object_id);

}  // namespace aperture::sim
