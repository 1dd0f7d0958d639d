// Renders the built-in `gap` scenario from the vehicle's start pose (aperture::sim) and detects the
// gap in that image (aperture::perception, seed 000 Sec. III-A), then compares the detected
// position of the gap in the camera frame with the renderer's ground truth.
//
// Prints the detection and exits 0 when the gap is found within 1 % of its distance, 1 when it is
// missed or off, 2 on an error.
#include <exception>
#include <iostream>

#include "perception/gap/gap_detector.h"
#include "sim/render/ray_caster.h"
#include "sim/scenario/scenario.h"

int main() {
  using namespace aperture;
  try {
    sim::Scenario scenario =
        sim::BuildScenario(sim::LoadScenarioParams(sim::ScenarioConfig("gap")));
    const sim::ScenarioCamera& camera = scenario.render_camera();
    const Eigen::Isometry3d T_WB = scenario.T_WB_start();
    scenario.SetVehiclePose(T_WB);
    const Eigen::Isometry3d T_WC = camera.T_WC(T_WB);
    sim::RayCaster caster;
    const sim::CapturedFrame captured = camera.effects.Capture(
        caster, scenario.scene(), *camera.model, [&](double) { return T_WC; }, 0.0, 0,
        camera.render);

    perception::GapDetector detector(perception::GapDetectorParams{}, camera.model);
    const perception::GapDetection detection = detector.Detect(captured.frame.image);
    const Eigen::Vector3d p_CG_true =
        T_WC.inverse() * scenario.scene().object("gap").T_WO.translation();
    std::cout << "image " << captured.frame.image.cols << "x" << captured.frame.image.rows
              << " from camera '" << camera.name << "', gap "
              << perception::GapDetectionStatusName(detection.status) << "\n";
    if (!detection.detected()) return 1;
    const Eigen::Vector3d p_CG = detection.T_CG.translation();
    const double error_m = (p_CG - p_CG_true).norm();
    std::cout << "p_CG = [" << p_CG.transpose() << "] m, ground truth [" << p_CG_true.transpose()
              << "] m, error " << error_m << " m at " << p_CG_true.norm() << " m\n";
    return error_m <= 0.01 * p_CG_true.norm() ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "gap_on_rendered_image: " << e.what() << "\n";
    return 2;
  }
}
