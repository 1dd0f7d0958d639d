#include "servo/internal/visp_conversions.h"

#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpTranslationVector.h>
#include <visp3/core/vpVelocityTwistMatrix.h>

namespace aperture::servo::internal {

vpHomogeneousMatrix ToVisp(const Eigen::Isometry3d& T_AB) {
  vpHomogeneousMatrix aMb;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) aMb[r][c] = T_AB.matrix()(r, c);
  }
  return aMb;
}

Eigen::Isometry3d FromVisp(const vpHomogeneousMatrix& aMb) {
  Eigen::Isometry3d T_AB = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) T_AB.matrix()(r, c) = aMb[r][c];
  }
  return T_AB;
}

Eigen::VectorXd ToEigen(const vpColVector& v) {
  Eigen::VectorXd result(v.size());
  for (unsigned int i = 0; i < v.size(); ++i) result[i] = v[i];
  return result;
}

Eigen::MatrixXd ToEigen(const vpMatrix& M) {
  Eigen::MatrixXd result(M.getRows(), M.getCols());
  for (unsigned int r = 0; r < M.getRows(); ++r) {
    for (unsigned int c = 0; c < M.getCols(); ++c) result(r, c) = M[r][c];
  }
  return result;
}

vpMatrix BodyDofJacobian(bool with_yaw_rate) {
  vpMatrix eJe(6, with_yaw_rate ? 4 : 3, 0.0);
  eJe[0][0] = eJe[1][1] = eJe[2][2] = 1.0;
  if (with_yaw_rate) eJe[5][3] = 1.0;
  return eJe;
}

void ConfigureDroneTask(const ServoGain& gain, const Eigen::Isometry3d& T_BC, bool with_yaw_rate,
                        vpServo* task) {
  task->setServo(vpServo::EYEINHAND_L_cVe_eJe);
  task->setInteractionMatrixType(vpServo::CURRENT);
  if (gain.at_zero_per_s == gain.at_infinity_per_s) {
    task->setLambda(gain.at_zero_per_s);  // vpAdaptiveGain divides by their difference
  } else {
    task->setLambda(gain.at_zero_per_s, gain.at_infinity_per_s, gain.slope_at_zero_per_s);
  }
  task->set_cVe(vpVelocityTwistMatrix(ToVisp(T_BC.inverse())));
  task->set_eJe(BodyDofJacobian(with_yaw_rate));
}

void FillReference(const vpColVector& u, const Eigen::Isometry3d& T_BC, BodyVelocityReference* ref,
                   Twist* twist_C) {
  ref->v_B = Eigen::Vector3d(u[0], u[1], u[2]);
  ref->yaw_rate_radps = u.size() > 3 ? u[3] : 0.0;
  *twist_C = CameraTwistFromBodyVelocity(*ref, T_BC);
}

}  // namespace aperture::servo::internal
