#pragma once
// The pose estimates of `aperture run`: one TUM trajectory file `<stream>.csv` per stream
// (`t tx ty tz qx qy qz qw`, one row per estimate) and, for streams with covariances,
// `<stream>_covariance.csv` (t and the 36 row-major entries of the 6x6 covariance of
// [translation; rotation]).
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "output/csv_writer.h"
#include "output/output_folder.h"
#include "output/tum_trajectory_writer.h"
#include "perception/graph/node.h"

namespace aperture::apps {

class PoseStreams {
 public:
  explicit PoseStreams(const output::OutputFolder& out) : out_(out) {}
  void Write(double t_s, const std::vector<perception::PoseObservation>& poses);
  // Finishes every file; returns {"<stream>": {"file", "estimates"}} for summary.json.
  nlohmann::json Close();

 private:
  struct Stream {
    std::unique_ptr<output::TumTrajectoryWriter> trajectory;
    std::unique_ptr<output::CsvWriter> covariance;
    std::size_t estimates = 0;
  };
  Stream& Open(const perception::PoseObservation& pose);

  const output::OutputFolder& out_;
  std::map<std::string, Stream> streams_;
};

}  // namespace aperture::apps
