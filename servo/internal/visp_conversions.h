#pragma once
// Eigen <-> ViSP at the servo library's call sites. INTERNAL: included by servo/*.cc only (ViSP
// is a private dependency of aperture::servo; no public header may include this one).
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/vs/vpServo.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "servo/body_velocity_reference.h"
#include "servo/servo_gain.h"

namespace aperture::servo::internal {

// T_AB (p_A = T_AB * p_B) as ViSP's aMb (same convention: ViSP's cMo is T_CO).
vpHomogeneousMatrix ToVisp(const Eigen::Isometry3d& T_AB);
Eigen::Isometry3d FromVisp(const vpHomogeneousMatrix& aMb);
Eigen::VectorXd ToEigen(const vpColVector& v);
Eigen::MatrixXd ToEigen(const vpMatrix& M);

// eJe of the commanded body DOFs (ViSP's drone form): columns v_x, v_y, v_z and, when
// with_yaw_rate, omega_z of the body twist [v_B; omega_B].
vpMatrix BodyDofJacobian(bool with_yaw_rate);

// Sets `task` up as EYEINHAND_L_cVe_eJe with the current interaction matrix, the gain and the
// camera mount (cVe from T_CB = T_BC^-1, ViSP's cMe).
void ConfigureDroneTask(const ServoGain& gain, const Eigen::Isometry3d& T_BC, bool with_yaw_rate,
                        vpServo* task);

// The body reference and camera twist of the task's output u (v_B or [v_B; yaw rate]).
void FillReference(const vpColVector& u, const Eigen::Isometry3d& T_BC, BodyVelocityReference* ref,
                   Twist* twist_C);

}  // namespace aperture::servo::internal
