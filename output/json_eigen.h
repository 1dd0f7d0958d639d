#pragma once
// Eigen values in summary.json: a vector (one column) becomes [x, y, z], a matrix a list of rows.
//   out.summary()["final"]["p_W_error_m"] = EigenToJson(p_W_error);
// Non-finite entries become null when dumped (JSON has no NaN).
#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace aperture::output {

template <typename Derived>
nlohmann::json EigenToJson(const Eigen::DenseBase<Derived>& value) {
  nlohmann::json json = nlohmann::json::array();
  if (value.cols() == 1) {
    for (Eigen::Index r = 0; r < value.rows(); ++r)
      json.push_back(static_cast<double>(value(r, 0)));
    return json;
  }
  for (Eigen::Index r = 0; r < value.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < value.cols(); ++c) row.push_back(static_cast<double>(value(r, c)));
    json.push_back(std::move(row));
  }
  return json;
}

}  // namespace aperture::output
