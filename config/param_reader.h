#pragma once
// ParamReader: typed, strict reading of one YAML map into a plain parameter struct (STYLE.md 6).
//
// A struct's loader reads every field it knows, then rejects whatever is left:
//
//   void LoadParams(config::ParamReader& reader, GapParams* params) {
//     reader.Read("roll_deg", &params->roll_deg);          // absent key: the in-class default
//     stays reader.ReadEnum("mode", &params->mode, {{"fast", Mode::kFast}, {"exact",
//     Mode::kExact}}); reader.ReadSection("detector", &params->detector);   // calls
//     LoadParams(reader, &detector) reader.RejectUnknownKeys();
//   }
//
// Errors are std::invalid_argument whose message starts with the location of the offending value
// ("gap.yaml:12:3" for a file, "--set gap.roll_deg=abc" for a command-line override), then the
// full dotted key and what was expected (the type, the allowed enum values, or the known keys).
//
// Supported field types: double, float, int, unsigned, std::size_t, bool, std::string, fixed-size
// Eigen matrices of double or int (vectors from a flat sequence, matrices from a sequence of rows
// or a flat row-major sequence), Eigen::VectorXd, std::vector<T> of any supported T, enums via
// ReadEnum, nested structs via ReadSection/Section.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include "config/param_archive.h"
#include "config/usage_error.h"

namespace aperture::config {

// Where a configuration value came from: a YAML file (line/column come from yaml-cpp marks), a
// "--set key=value" item, or built-in default text. Keyed by dotted path ("gap.roll_deg"); the
// longest recorded prefix of a path names its source.
struct ValueOrigin {
  std::string source;      // file path, "--set key=value", or a label such as "built-in defaults"
  bool has_lines = false;  // true when marks in the node refer to lines of `source`
  bool command_line = false;  // a --set item: its errors are usage errors (config::UsageError)
};
using OriginMap = std::map<std::string, ValueOrigin>;

// ---- Conversion of one YAML node into a typed value --------------------------------------------
// `where` and `key` only feed error messages. Each throws std::invalid_argument on mismatch, a
// config::UsageError when `command_line` (the value came from a --set item).
struct ValueContext {
  std::string where;  // "file.yaml:12:3" or "--set a.b=1"
  std::string key;    // full dotted key
  bool command_line = false;
  bool allow_infinite = false;  // ReadLimit: .inf/-.inf mean "no limit"

  // The context of an element: key + `suffix` ("[2]").
  ValueContext Element(const std::string& suffix) const {
    ValueContext element = *this;
    element.key += suffix;
    return element;
  }
};

class ParamReader {
 public:
  // Reads `node` (a map; null or undefined means "all defaults") found at dotted `path` ("" at the
  // root). `origins` resolves locations for error messages.
  ParamReader(YAML::Node node, std::string path, std::shared_ptr<const OriginMap> origins);
  // Convenience for a standalone document: every value comes from `source` (e.g. a file name).
  ParamReader(YAML::Node node, const std::string& source);

  // Overwrites *value when `key` is present; otherwise leaves the default. Throws
  // std::invalid_argument naming location, key and expected type on a type mismatch (a
  // config::UsageError when the value came from a --set item). Numbers must be finite and within
  // the range of their unit (ConvertNode(double)); an infinite value only where the default is
  // infinite ("no limit", e.g. min_height_m: -.inf), see ReadLimit.
  template <typename T>
  void Read(const std::string& key, T* value);
  // A number that may also be .inf or -.inf, meaning "no limit" (e.g. mahalanobis_gate: .inf
  // disables gating); NaN is still rejected.
  void ReadLimit(const std::string& key, double* value);

  // Reads a string and maps it through `allowed` (name → enum value). An unknown name throws,
  // listing the allowed names.
  template <typename Enum>
  void ReadEnum(const std::string& key, Enum* value,
                const std::vector<std::pair<std::string, Enum>>& allowed);

  // Reader for the nested map at `key` (empty reader when absent). Marks `key` as known.
  ParamReader Section(const std::string& key);

  // Nested struct: calls LoadParams(ParamReader&, T*) (found by argument-dependent lookup) on
  // Section(key), then rejects unknown keys inside it.
  template <typename T>
  void ReadSection(const std::string& key, T* value);

  // Validates `params` (ValidateLoaded: its ValidateParams hook or Validate() member) and re-throws
  // the std::invalid_argument in the user's terms: a struct-qualified field in the message
  // ("GapMissionParams.hover_s", "TraverseParameters: max_evaluations =") becomes the key path
  // of the section that struct was loaded from ("mission.hover_s"), and the message starts with
  // where that value came from (file:line:column or the --set item), so a non-physical value
  // names the file (or --set item) and key to fix.
  template <typename Params>
  void Validate(const Params& params) const;

  // True when `key` is present in the map (does not mark it as known).
  bool Has(const std::string& key) const;

  // Keys present in the map, in document order (empty for an absent section). For maps keyed by
  // user-chosen names (e.g. scenario objects); does not mark them as known.
  std::vector<std::string> Keys() const;

  // Throws std::invalid_argument for the first key present in the map that no Read*/Section call
  // asked for, naming its location and listing the known keys.
  void RejectUnknownKeys() const;
  // For a map keyed by names (scenario cameras, objects): a `--set` item adds to an existing entry
  // but cannot create one, so `--set cameras.frnt.rate_hz=30` is a typo rather than a second
  // camera. Throws config::UsageError naming the item and listing the names `entry_kind` has
  // (a new entry belongs in a --config file). With a `declaring_key`, --set may create an entry
  // by setting that key (`objects.crate.shape=box` declares the object crate), so only an entry
  // that --set items create without it (`objects.crat.radius_m=1`, a typo) is refused.
  void RejectEntriesCreatedBySet(const std::string& entry_kind,
                                 const std::string& declaring_key = "") const;
  // Throws the error about the value at `key`: "<where>: '<full key>' <what>", a
  // config::UsageError when the value came from a --set item, else std::invalid_argument.
  [[noreturn]] void Fail(const std::string& key, const std::string& what) const;

  // "file.yaml:12:3", "--set a.b=1" or the source label: where the value at `key` came from.
  std::string Where(const std::string& key) const;
  // Dotted path of `key` inside this reader ("gap.roll_deg").
  std::string FullKey(const std::string& key) const;

 private:
  YAML::Node Lookup(const std::string& key);  // marks key as known
  std::string Locate(const std::string& full_key, const YAML::Mark& mark) const;
  // The origin recorded for the longest prefix of `full_key` (nullptr when none is).
  const ValueOrigin* OriginOf(const std::string& full_key) const;
  ValueContext ContextOf(const std::string& key, const YAML::Node& child) const;
  // The --set items that set values inside this section ("" when none did).
  std::string CommandLineItemsInside() const;
  // Validate's halves: records that this section holds a `type`; throws the validation error
  // `what` of a `type` in the user's terms (see Validate).
  void NoteSectionType(const std::type_info& type) const;
  [[noreturn]] void FailValidation(const std::type_info& type, const std::string& what) const;

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<const OriginMap> origins_;
  std::set<std::string> known_keys_;
  // Struct name -> key paths of the sections validated as that struct, shared by every reader of
  // one tree (Section passes it on): a message naming a nested struct's field finds its key.
  std::shared_ptr<std::map<std::string, std::set<std::string>>> section_types_;
};

[[noreturn]] void ThrowTypeError(const ValueContext& context, const YAML::Node& node,
                                 const std::string& expected);
void ConvertNode(const YAML::Node& node, const ValueContext& context, double* value);
void ConvertNode(const YAML::Node& node, const ValueContext& context, float* value);
void ConvertNode(const YAML::Node& node, const ValueContext& context, int* value);
// Unsigned: counts, sizes and random seeds; a negative value is a type error.
void ConvertNode(const YAML::Node& node, const ValueContext& context, unsigned int* value);
void ConvertNode(const YAML::Node& node, const ValueContext& context, unsigned long* value);
void ConvertNode(const YAML::Node& node, const ValueContext& context, bool* value);
void ConvertNode(const YAML::Node& node, const ValueContext& context, std::string* value);
void ConvertNode(const YAML::Node& node, const ValueContext& context, Eigen::VectorXd* value);

template <typename T>
void ConvertNode(const YAML::Node& node, const ValueContext& context, std::vector<T>* value) {
  if (!node.IsSequence()) ThrowTypeError(context, node, "a sequence [..]");
  std::vector<T> result(node.size());
  for (std::size_t i = 0; i < node.size(); ++i) {
    ConvertNode(node[i], context.Element("[" + std::to_string(i) + "]"), &result[i]);
  }
  *value = std::move(result);
}

// Fixed-size Eigen of double or int: a vector (one column) from [x, y, z]; a matrix from [[row0],
// [row1], ..] or a flat row-major list of Rows*Cols numbers.
template <typename Scalar, int Rows, int Cols, int Options>
void ConvertNode(const YAML::Node& node, const ValueContext& context,
                 Eigen::Matrix<Scalar, Rows, Cols, Options, Rows, Cols>* value) {
  static_assert(Rows > 0 && Cols > 0, "use Eigen::VectorXd or std::vector for dynamic sizes");
  const std::string shape = Cols == 1 ? "a sequence of " + std::to_string(Rows) + " numbers"
                                      : "a " + std::to_string(Rows) + "x" + std::to_string(Cols) +
                                            " matrix as " + std::to_string(Rows) + " rows of " +
                                            std::to_string(Cols) + " numbers or " +
                                            std::to_string(Rows * Cols) + " numbers row-major";
  if (!node.IsSequence()) ThrowTypeError(context, node, shape);
  Eigen::Matrix<Scalar, Rows, Cols, Options, Rows, Cols> result = *value;  // defaults per element
  if (node.size() == static_cast<std::size_t>(Rows * Cols) &&
      (Cols == 1 || !node[0].IsSequence())) {
    for (int i = 0; i < Rows * Cols; ++i) {
      ConvertNode(node[i], context.Element("[" + std::to_string(i) + "]"),
                  &result(i / Cols, i % Cols));
    }
  } else if (Cols > 1 && node.size() == static_cast<std::size_t>(Rows)) {
    for (int r = 0; r < Rows; ++r) {
      const YAML::Node row = node[r];
      if (!row.IsSequence() || row.size() != static_cast<std::size_t>(Cols)) {
        ThrowTypeError(context, node, shape);
      }
      for (int c = 0; c < Cols; ++c) {
        ConvertNode(row[c],
                    context.Element("[" + std::to_string(r) + "][" + std::to_string(c) + "]"),
                    &result(r, c));
      }
    }
  } else {
    ThrowTypeError(context, node, shape);
  }
  *value = result;
}

// ---- Template definitions ----------------------------------------------------------------------

template <typename T>
void ParamReader::Read(const std::string& key, T* value) {
  const YAML::Node child = Lookup(key);
  if (!child) return;
  ConvertNode(child, ContextOf(key, child), value);
}

template <typename Enum>
void ParamReader::ReadEnum(const std::string& key, Enum* value,
                           const std::vector<std::pair<std::string, Enum>>& allowed) {
  const YAML::Node child = Lookup(key);
  if (!child) return;
  std::string allowed_list;
  for (const auto& [name, unused] : allowed) {
    allowed_list += (allowed_list.empty() ? "" : ", ") + name;
  }
  const ValueContext context = ContextOf(key, child);
  std::string name;
  if (!child.IsScalar()) ThrowTypeError(context, child, "one of: " + allowed_list);
  ConvertNode(child, context, &name);
  for (const auto& [candidate, enum_value] : allowed) {
    if (candidate == name) {
      *value = enum_value;
      return;
    }
  }
  ThrowTypeError(context, child, "one of: " + allowed_list);
}

template <typename Params>
void ParamReader::Validate(const Params& params) const {
  NoteSectionType(typeid(Params));
  try {
    ValidateLoaded(params);
  } catch (const std::invalid_argument& e) {
    FailValidation(typeid(Params), e.what());
  }
}

template <typename T>
void ParamReader::ReadSection(const std::string& key, T* value) {
  ParamReader section = Section(key);
  LoadParams(section, value);
  section.RejectUnknownKeys();
}

}  // namespace aperture::config
