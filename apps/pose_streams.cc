#include "apps/pose_streams.h"

namespace aperture::apps {

PoseStreams::Stream& PoseStreams::Open(const perception::PoseObservation& pose) {
  Stream& stream = streams_[pose.stream];
  if (!stream.trajectory) {
    stream.trajectory =
        std::make_unique<output::TumTrajectoryWriter>(out_.Path(pose.stream + ".csv"));
  }
  if (pose.covariance_CX && !stream.covariance) {
    std::vector<std::string> columns{"t_s"};
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) columns.push_back("c" + std::to_string(r) + std::to_string(c));
    }
    stream.covariance =
        std::make_unique<output::CsvWriter>(out_.Path(pose.stream + "_covariance.csv"), columns);
  }
  return stream;
}

void PoseStreams::Write(double t_s, const std::vector<perception::PoseObservation>& poses) {
  for (const perception::PoseObservation& pose : poses) {
    Stream& stream = Open(pose);
    stream.trajectory->Write(t_s, pose.T_fixed_moving());
    ++stream.estimates;
    if (pose.covariance_CX && stream.covariance) {
      const Eigen::Matrix<double, 6, 6> covariance = *pose.covariance_fixed_moving();
      std::vector<double> row{t_s};
      for (int r = 0; r < 6; ++r) {
        for (int c = 0; c < 6; ++c) row.push_back(covariance(r, c));
      }
      stream.covariance->WriteRow(row);
    }
  }
}

nlohmann::json PoseStreams::Close() {
  nlohmann::json summary = nlohmann::json::object();
  for (auto& [name, stream] : streams_) {
    stream.trajectory->Close();
    if (stream.covariance) stream.covariance->Close();
    summary[name] = {{"file", name + ".csv"}, {"estimates", stream.estimates}};
  }
  return summary;
}

}  // namespace aperture::apps
