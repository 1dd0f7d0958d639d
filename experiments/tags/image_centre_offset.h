#pragma once
// How far from the image centre a body-mounted camera sees a point, on ground truth: the measure
// of issue 16's tag servo ("keeps the robot's tag within 10 % of the image width of the image
// centre").
#include <Eigen/Geometry>
#include <optional>

#include "control/quad_state.h"
#include "perception/camera/camera_model.h"

namespace aperture::experiments {

// |projection of p_W - image centre| / image width for the camera mounted at T_BC (p_B = T_BC
// p_C) on the vehicle in state x; std::nullopt when p_W does not project into the camera.
std::optional<double> ImageCentreOffset(const control::QuadState& x, const Eigen::Isometry3d& T_BC,
                                        const perception::CameraModel& camera,
                                        const Eigen::Vector3d& p_W);

}  // namespace aperture::experiments
