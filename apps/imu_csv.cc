#include "apps/imu_csv.h"

namespace aperture::apps {

std::unique_ptr<output::CsvWriter> MakeImuCsv(const std::string& path) {
  return std::make_unique<output::CsvWriter>(
      path, std::vector<std::string>{"t_s", "acc_x_mps2", "acc_y_mps2", "acc_z_mps2",
                                     "gyro_x_radps", "gyro_y_radps", "gyro_z_radps"});
}

void WriteImuRow(output::CsvWriter& csv, const perception::ImuSample& sample) {
  csv.WriteRow({sample.t_s, sample.specific_force_B.x(), sample.specific_force_B.y(),
                sample.specific_force_B.z(), sample.omega_B.x(), sample.omega_B.y(),
                sample.omega_B.z()});
}

}  // namespace aperture::apps
