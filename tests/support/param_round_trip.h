#pragma once
// Round-trip check of a Serialize-described parameter struct (config/param_archive.h): every field
// is moved off its value (PerturbArchive), dumped (config::DumpParams), loaded into a
// default-constructed struct with the strict loader, and dumped again. The two dumps must be the
// same text (shortest round-trip numbers: equal text = bit-identical values), and every key of the
// dump must differ from the unperturbed dump, so no field is left out of either direction.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "config/yaml_read_archive.h"
#include "config/yaml_write_archive.h"

namespace aperture::test_support {

// Changes every field it visits: numbers by a relative 1/3000 (a zero to 1/1024), which keeps
// orderings between fields (min < max) and gives digits that need the full precision; integers
// +1, booleans flipped, strings extended, enums to the next name. Containers: their elements.
class PerturbArchive {
 public:
  static constexpr bool kLoading = true;  // Serialize applies presets as when loading

  template <typename T>
  void Visit(const char*, T* value) {
    Perturb(value);
  }
  template <typename Enum>
  void Visit(const char*, Enum* value, const config::EnumNames<Enum>& names) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i].second == *value) {
        *value = names[(i + 1) % names.size()].second;
        return;
      }
    }
  }
  void VisitLimit(const char*, double* value) { Perturb(value); }
  template <typename Function>
  void VisitSection(const char*, const Function& describe) {
    describe(this);
  }

 private:
  static void Perturb(double* x) { *x = *x == 0.0 ? 1.0 / 1024.0 : *x * (1.0 + 1.0 / 3000.0); }
  static void Perturb(float* x) { *x = *x == 0.0f ? 1.0f / 1024.0f : *x * (1.0f + 1.0f / 3000.0f); }
  static void Perturb(int* x) { *x += 1; }
  static void Perturb(unsigned int* x) { *x += 1; }
  static void Perturb(unsigned long* x) { *x += 1; }
  static void Perturb(bool* x) { *x = !*x; }
  static void Perturb(std::string* x) { *x += "_x"; }
  template <typename Scalar, int Rows, int Cols, int Options, int MaxRows, int MaxCols>
  static void Perturb(Eigen::Matrix<Scalar, Rows, Cols, Options, MaxRows, MaxCols>* m) {
    for (Eigen::Index i = 0; i < m->size(); ++i) Perturb(&m->data()[i]);
  }
  template <typename T>
  void Perturb(std::vector<T>* values) {
    for (T& value : *values) Perturb(&value);
  }
  template <typename T>
  void Perturb(T* value) {
    if constexpr (config::kIsSerializable<T>) {
      Serialize(this, value);
    } else {
      // A leaf type with its own format (e.g. a gust as a list): perturb the numbers of its YAML.
      YAML::Node node = config::YamlWriteArchive::Encode(*value);
      PerturbNumbers(&node);
      ConvertNode(node, config::ValueContext{"perturbed", "leaf"}, value);
    }
  }
  static void PerturbNumbers(YAML::Node* node) {
    if (node->IsSequence()) {
      for (std::size_t i = 0; i < node->size(); ++i) {
        YAML::Node child = (*node)[i];
        PerturbNumbers(&child);
      }
    } else if (node->IsScalar()) {
      double x = std::stod(node->Scalar());
      Perturb(&x);
      *node = config::EncodeNode(x);
    }
  }
};

// Dotted key -> YAML text of every leaf of a dump.
inline void FlattenInto(const YAML::Node& node, const std::string& path,
                        std::map<std::string, std::string>* leaves) {
  if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      FlattenInto(it->second, path.empty() ? it->first.Scalar() : path + "." + it->first.Scalar(),
                  leaves);
    }
    return;
  }
  (*leaves)[path] = config::ToYamlText(node);
}

// Keys allowed to keep their value under PerturbArchive (e.g. an empty list).
template <typename T>
void ExpectRoundTrip(const T& base, const std::vector<std::string>& unchanged_keys = {}) {
  T perturbed = base;
  PerturbArchive perturb;
  Serialize(&perturb, &perturbed);
  const YAML::Node dump = config::DumpParams(perturbed);

  std::map<std::string, std::string> before, after;
  FlattenInto(config::DumpParams(base), "", &before);
  FlattenInto(dump, "", &after);
  ASSERT_EQ(before.size(), after.size());
  for (const auto& [key, text] : after) {
    bool allowed = false;
    for (const std::string& unchanged : unchanged_keys) allowed = allowed || unchanged == key;
    if (!allowed) {
      EXPECT_NE(before[key], text) << key << " was not perturbed";
    }
  }

  // Through text, as a file or summary.json would carry it.
  const std::string text = config::ToYamlText(dump);
  config::ParamReader reader(YAML::Load(text), "dump.yaml");
  T loaded;
  LoadParams(reader, &loaded);
  EXPECT_EQ(config::DumpYaml(loaded), text);
}

}  // namespace aperture::test_support
