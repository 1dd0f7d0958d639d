#include "output/tum_trajectory_writer.h"

#include <cmath>
#include <stdexcept>

#include "output/number_format.h"

namespace aperture::output {

TumTrajectoryWriter::TumTrajectoryWriter(const std::string& path) : file_(path) {
  file_.stream() << "# timestamp tx ty tz qx qy qz qw\n";
}

void TumTrajectoryWriter::Write(double t_s, const Eigen::Vector3d& p_WB,
                                const Eigen::Quaterniond& q_WB) {
  const double norm = q_WB.norm();
  if (!std::isfinite(t_s) || !p_WB.allFinite() || !q_WB.coeffs().allFinite() || norm < 1e-12) {
    throw std::invalid_argument("pose at t=" + FormatDouble(t_s) + " s for '" + file_.path() +
                                "' is not finite or has a zero quaternion; fix the estimate "
                                "before writing it");
  }
  const Eigen::Quaterniond q = q_WB.normalized();
  std::ostream& out = file_.stream();
  out << FormatDouble(t_s) << ' ' << FormatDouble(p_WB.x()) << ' ' << FormatDouble(p_WB.y()) << ' '
      << FormatDouble(p_WB.z()) << ' ' << FormatDouble(q.x()) << ' ' << FormatDouble(q.y()) << ' '
      << FormatDouble(q.z()) << ' ' << FormatDouble(q.w()) << '\n';
  ++poses_written_;
}

void TumTrajectoryWriter::Write(double t_s, const Eigen::Isometry3d& T_WB) {
  Write(t_s, T_WB.translation(), Eigen::Quaterniond(T_WB.rotation()));
}

}  // namespace aperture::output
