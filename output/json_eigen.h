#pragma once
// Eigen values in summary.json: a vector (one column) becomes [x, y, z], a matrix a list of rows.
//   out.summary()["final"]["p_W_error_m"] = EigenToJson(p_W_error);
// Non-finite entries become null when dumped (JSON has no NaN).
// JsonToVector<N> reads such a list back (records that shards store, experiments/bench/).
#include <Eigen/Core>
#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

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

// A list of N numbers as a vector; std::invalid_argument quoting `json` otherwise.
template <int N>
Eigen::Matrix<double, N, 1> JsonToVector(const nlohmann::json& json) {
  if (!json.is_array() || json.size() != N ||
      !std::all_of(json.begin(), json.end(), [](const nlohmann::json& v) { return v.is_number(); })) {
    throw std::invalid_argument("expected a list of " + std::to_string(N) + " numbers, got " +
                                json.dump());
  }
  Eigen::Matrix<double, N, 1> vector;
  for (int i = 0; i < N; ++i) vector(i) = json[static_cast<std::size_t>(i)].get<double>();
  return vector;
}

}  // namespace aperture::output
