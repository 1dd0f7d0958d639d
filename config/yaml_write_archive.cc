#include "config/yaml_write_archive.h"

#include <charconv>
#include <cmath>
#include <regex>
#include <system_error>

namespace aperture::config {

YAML::Node EncodeNode(double value) {
  if (std::isnan(value)) return YAML::Node(".nan");
  if (std::isinf(value)) return YAML::Node(value > 0.0 ? ".inf" : "-.inf");
  // Shortest decimal text that strtod reads back to the same double.
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return YAML::Node(std::string(buffer, result.ptr));
}

YAML::Node EncodeNode(float value) {
  if (!std::isfinite(value)) return EncodeNode(static_cast<double>(value));
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return YAML::Node(std::string(buffer, result.ptr));
}

YAML::Node EncodeNode(int value) { return YAML::Node(std::to_string(value)); }
YAML::Node EncodeNode(unsigned int value) { return YAML::Node(std::to_string(value)); }
YAML::Node EncodeNode(unsigned long value) { return YAML::Node(std::to_string(value)); }
YAML::Node EncodeNode(bool value) { return YAML::Node(value ? "true" : "false"); }

YAML::Node EncodeNode(const std::string& value) {
  YAML::Node node(value);
  // Text a plain scalar would turn into another type (ConfigTree::ToJson, YAML readers) keeps
  // the non-specific tag of a quoted scalar.
  static const std::regex kOtherType(
      R"([-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?|[-+]?\.?(inf|Inf|INF|nan|NaN|NAN)|)"
      R"(true|True|TRUE|false|False|FALSE|null|Null|NULL|~|)");
  if (std::regex_match(value, kOtherType)) node.SetTag("!");
  return node;
}

YAML::Node EncodeNode(const Eigen::VectorXd& value) {
  YAML::Node node(YAML::NodeType::Sequence);
  node.SetStyle(YAML::EmitterStyle::Flow);
  for (Eigen::Index i = 0; i < value.size(); ++i) node.push_back(EncodeNode(value[i]));
  return node;
}

std::string ToYamlText(const YAML::Node& node) {
  YAML::Emitter emitter;
  emitter << node;
  return std::string(emitter.c_str()) + "\n";
}

}  // namespace aperture::config
