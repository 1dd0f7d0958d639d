#pragma once
// One list of (key, field) pairs per record struct gives both directions of its JSON form (the
// records that shards store for `aperture bench merge`). The list is a generic lambda, so the
// same text visits a const struct when writing and a mutable one when reading:
//
//   constexpr auto kRangesFields = [](auto& f, auto& r) {
//     f("max_roll_deg", r.max_roll_deg);
//     f("distance_m", r.distance_m);               // Eigen vectors as [x, y, ...]
//     f("status", r.status, kStatusNames);         // enums by name
//   };
//   nlohmann::json json = output::FieldsToJson(ranges, kRangesFields);
//   Ranges read = output::FieldsFromJson<Ranges>(json, kRangesFields);  // json.at() per key
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "output/json_eigen.h"

namespace aperture::output {

template <typename Enum>
using JsonEnumNames = std::vector<std::pair<std::string, Enum>>;

namespace internal {

template <typename T, typename = void>
struct IsEigenVector : std::false_type {};
template <typename T>
struct IsEigenVector<T, std::enable_if_t<std::is_base_of_v<Eigen::MatrixBase<T>, T>>>
    : std::bool_constant<T::ColsAtCompileTime == 1> {};
template <typename T>
inline constexpr bool kIsEigenVector = IsEigenVector<T>::value;

class JsonFieldWriter {
 public:
  template <typename T>
  void operator()(const char* key, const T& value) {
    if constexpr (kIsEigenVector<T>) {
      json_[key] = EigenToJson(value);
    } else {
      json_[key] = value;
    }
  }
  template <typename Enum>
  void operator()(const char* key, const Enum& value, const JsonEnumNames<Enum>& names) {
    for (const auto& [name, v] : names) {
      if (v == value) {
        json_[key] = name;
        return;
      }
    }
    throw std::invalid_argument(std::string("JSON field ") + key + ": an enum value without a name");
  }
  nlohmann::json& json() { return json_; }

 private:
  nlohmann::json json_ = nlohmann::json::object();
};

class JsonFieldReader {
 public:
  explicit JsonFieldReader(const nlohmann::json& json) : json_(json) {}
  template <typename T>
  void operator()(const char* key, T& value) const {
    if constexpr (kIsEigenVector<T>) {
      value = JsonToVector<T::RowsAtCompileTime>(json_.at(key));
    } else {
      value = json_.at(key).template get<T>();
    }
  }
  template <typename Enum>
  void operator()(const char* key, Enum& value, const JsonEnumNames<Enum>& names) const {
    const std::string name = json_.at(key).get<std::string>();
    for (const auto& [n, v] : names) {
      if (n == name) {
        value = v;
        return;
      }
    }
    throw std::invalid_argument(std::string("JSON field ") + key + ": unknown value \"" + name +
                                "\"");
  }

 private:
  const nlohmann::json& json_;
};

}  // namespace internal

// Every field `visit` names, as one JSON object.
template <typename T, typename Visit>
nlohmann::json FieldsToJson(const T& value, const Visit& visit) {
  internal::JsonFieldWriter writer;
  visit(writer, value);
  return std::move(writer.json());
}

// A T whose visited fields are read from `json` (nlohmann::json::exception for a missing key or a
// wrong type, std::invalid_argument for a malformed vector or an unknown enum name).
template <typename T, typename Visit>
T FieldsFromJson(const nlohmann::json& json, const Visit& visit) {
  T value;
  const internal::JsonFieldReader reader(json);
  visit(reader, value);
  return value;
}

}  // namespace aperture::output
