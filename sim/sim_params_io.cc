#include "sim/sim_params_io.h"

namespace aperture::sim {

void ConvertNode(const YAML::Node& node, const config::ValueContext& context, WindGust* gust) {
  Eigen::Matrix<double, 5, 1> row;
  config::ConvertNode(node, context, &row);
  *gust = WindGust{row[0], row[1], row.tail<3>()};
}

void ConvertNode(const YAML::Node& node, const config::ValueContext& context, Push* push) {
  Eigen::VectorXd row;
  config::ConvertNode(node, context, &row);
  if (row.size() != 4 && row.size() != 7) {
    config::ThrowTypeError(context, node,
                           "[t_s, J_x, J_y, J_z] or [t_s, J_x, J_y, J_z, L_x, L_y, L_z]");
  }
  *push = Push{row[0], row.segment<3>(1), Eigen::Vector3d::Zero()};
  if (row.size() == 7) push->angular_impulse_B_Nms = row.tail<3>();
}

YAML::Node EncodeNode(const WindGust& gust) {
  Eigen::Matrix<double, 5, 1> row;
  row << gust.t_start_s, gust.duration_s, gust.wind_W_mps;
  return config::EncodeNode(row);
}

YAML::Node EncodeNode(const Push& push) {
  const bool angular = !push.angular_impulse_B_Nms.isZero(0.0);
  Eigen::VectorXd row(angular ? 7 : 4);
  row.head<4>() << push.t_s, push.impulse_W_Ns;
  if (angular) row.tail<3>() = push.angular_impulse_B_Nms;
  return config::EncodeNode(row);
}

}  // namespace aperture::sim
