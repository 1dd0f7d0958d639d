#pragma once
// YamlWriteArchive: the dump side of a struct's Serialize (param_archive.h). Every field becomes
// a key of a YAML map, in Serialize order, in the format the loader reads, so that
// LoadParams(ParamReader(DumpParams(p), ...), &q) gives q == p bit for bit (numbers in the
// shortest text that reads back exactly; .nan/.inf/-.inf for non-finite values).
//
//   YAML::Node mission = config::DumpParams(mission_params);   // documented defaults:
//   std::cout << config::DumpYaml(planning::GapMissionParams{});
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "config/param_archive.h"

namespace aperture::config {

// ---- One value as a YAML node (the inverse of ConvertNode in param_reader.h) ------------------
YAML::Node EncodeNode(double value);
YAML::Node EncodeNode(float value);
YAML::Node EncodeNode(int value);
YAML::Node EncodeNode(unsigned int value);
YAML::Node EncodeNode(unsigned long value);
YAML::Node EncodeNode(bool value);
// Tagged as a string ("!") when the text would otherwise read as a number, boolean or null.
YAML::Node EncodeNode(const std::string& value);
YAML::Node EncodeNode(const Eigen::VectorXd& value);

template <typename T>
YAML::Node EncodeNode(const std::vector<T>& values);

// Fixed-size Eigen: a vector as [x, y, z], a matrix as rows [[..], [..]].
template <typename Scalar, int Rows, int Cols, int Options>
YAML::Node EncodeNode(const Eigen::Matrix<Scalar, Rows, Cols, Options, Rows, Cols>& value) {
  YAML::Node node(YAML::NodeType::Sequence);
  node.SetStyle(YAML::EmitterStyle::Flow);
  for (int r = 0; r < Rows; ++r) {
    if (Cols == 1) {
      node.push_back(EncodeNode(value(r, 0)));
      continue;
    }
    YAML::Node row(YAML::NodeType::Sequence);
    row.SetStyle(YAML::EmitterStyle::Flow);
    for (int c = 0; c < Cols; ++c) row.push_back(EncodeNode(value(r, c)));
    node.push_back(row);
  }
  return node;
}

class YamlWriteArchive {
 public:
  static constexpr bool kLoading = false;

  YamlWriteArchive() : node_(YAML::NodeType::Map) {}

  template <typename T>
  void Visit(const char* name, T* value) {
    node_[name] = Encode(*value);
  }
  template <typename Enum>
  void Visit(const char* name, Enum* value, const EnumNames<Enum>& names) {
    for (const auto& [text, candidate] : names) {
      if (candidate == *value) {
        node_[name] = EncodeNode(text);
        return;
      }
    }
    node_[name] = EncodeNode(std::string("<unnamed value>"));  // names lists every enumerator
  }
  void VisitLimit(const char* name, double* value) { Visit(name, value); }
  template <typename Function>
  void VisitSection(const char* name, const Function& describe) {
    YamlWriteArchive archive;
    describe(&archive);
    node_[name] = archive.node();
  }

  const YAML::Node& node() const { return node_; }

  // A leaf through EncodeNode, a Serialize-described struct as a map.
  template <typename T>
  static YAML::Node Encode(const T& value) {
    if constexpr (kIsSerializable<T>) {
      YamlWriteArchive archive;
      Serialize(&archive, const_cast<T*>(&value));  // the write archive only reads the fields
      return archive.node();
    } else {
      return EncodeNode(value);
    }
  }

 private:
  YAML::Node node_;
};

template <typename T>
YAML::Node EncodeNode(const std::vector<T>& values) {
  YAML::Node node(YAML::NodeType::Sequence);
  node.SetStyle(YAML::EmitterStyle::Flow);
  for (const T& value : values) node.push_back(YamlWriteArchive::Encode(value));
  return node;
}

// Every field of `params` as a YAML map (Serialize order).
template <typename T>
YAML::Node DumpParams(const T& params) {
  static_assert(kIsSerializable<T>, "DumpParams needs a Serialize(Archive*, T*) overload");
  return YamlWriteArchive::Encode(params);
}

// DumpParams as YAML text (block style for maps).
std::string ToYamlText(const YAML::Node& node);
template <typename T>
std::string DumpYaml(const T& params) {
  return ToYamlText(DumpParams(params));
}

}  // namespace aperture::config
