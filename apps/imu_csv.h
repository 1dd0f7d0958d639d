#pragma once
// OUT/imu.csv, one row per IMU sample as delivered (t_s, accelerometer [m/s^2], gyroscope
// [rad/s] in B): written by `aperture sim` and by `aperture run` of a bag with --imu-topic.
#include <memory>
#include <string>

#include "output/csv_writer.h"
#include "perception/sensor_data.h"

namespace aperture::apps {

std::unique_ptr<output::CsvWriter> MakeImuCsv(const std::string& path);
void WriteImuRow(output::CsvWriter& csv, const perception::ImuSample& sample);

}  // namespace aperture::apps
