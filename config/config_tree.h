#pragma once
// ConfigTree: the effective configuration of one command, layered as
//   built-in defaults (YAML text)  <  --config FILE (YAML, in order)  <  --set key=value (in order)
// Later layers win. Maps merge key by key; scalars and sequences are replaced whole.
//
// Every value keeps where it came from, so a ParamReader error names "file.yaml:12:3" for a value
// from a file and "--set gap.roll_deg=abc" for a command-line override (see param_reader.h).
//
//   ConfigTree tree = ConfigTree::FromCommandLine(kDefaultsYaml, config_files, set_items);
//   config::ParamReader root = tree.Reader();
//   root.ReadSection("gap", &gap_params);   // LoadParams(ParamReader&, GapParams*)
//   root.RejectUnknownKeys();               // typo'd top-level sections fail loudly
#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "config/yaml_write_archive.h"

namespace aperture::config {

class ConfigTree {
 public:
  ConfigTree();

  // All layers in order. `defaults_yaml` may be empty. Throws like the methods below.
  static ConfigTree FromCommandLine(const std::string& defaults_yaml,
                                    const std::vector<std::string>& config_files,
                                    const std::vector<std::string>& set_items);

  // Merges a YAML document whose top level is a map. `source` labels it in error messages (a file
  // path or e.g. "built-in defaults"); line numbers refer to `yaml_text`. Throws
  // std::invalid_argument on a YAML syntax error or a non-map document, naming `source`.
  void MergeYaml(const std::string& yaml_text, const std::string& source);
  // Reads and merges a YAML file. A run's summary.json (a JSON map with "command" and a "config"
  // map) contributes its "config" section: the full effective configuration that run used, so
  // `--config OUT/summary.json` repeats it. std::runtime_error when it cannot be read (names the
  // path).
  void MergeFile(const std::string& path);
  // Applies one "dotted.key=value" override; the value is parsed as YAML ("30", "lqr",
  // "[[0,0,0],[1,0,0]]"). std::invalid_argument naming the item when there is no '=', the key is
  // empty or has an empty segment ("a..b"), or the value is not valid YAML.
  void ApplySet(const std::string& item);

  // Replaces the value at top-level `key` by `value` (e.g. the dump of a parameter struct's
  // effective values, config::DumpParams); `source` labels it in error messages.
  void Put(const std::string& key, const YAML::Node& value, const std::string& source);
  // Every field of a Serialize-described struct (config::DumpParams) as section `key`: how a
  // command records the effective values it ran with (summary.json "config").
  template <typename T>
  void PutParams(const std::string& key, const T& params) {
    Put(key, DumpParams(params), "effective configuration");
  }

  ParamReader Reader() const;
  // Effective configuration as YAML text (for logs or a config.yaml next to the results).
  std::string ToYaml() const;
  // Effective configuration as compact JSON text, for summary.json:
  //   out.summary()["config"] = nlohmann::json::parse(tree.ToJson());
  // Plain scalars become JSON numbers (decimal YAML numbers), booleans (true/false), null
  // (null, ~, empty) or strings; quoted YAML scalars always stay strings. Non-finite numbers
  // (.nan, .inf), which JSON cannot hold, stay strings.
  std::string ToJson() const;
  const YAML::Node& root() const { return root_; }
  // The --set item that set a key `message` names as a whole word (e.g. "cameras.front.rate_hz =
  // 1e+12 exceeds sitl.dynamics_rate_hz" after --set cameras.front.rate_hz=1e12; the longest such
  // key), "" when it names none: an error about that value is a usage error.
  std::string SetItemNamedIn(const std::string& message) const;

 private:
  void MergeDocument(const YAML::Node& document, const std::string& source);
  void MergeNode(YAML::Node destination, const YAML::Node& source, const std::string& path,
                 const ValueOrigin& origin);
  void RecordOrigin(const std::string& path, const ValueOrigin& origin);

  YAML::Node root_;
  OriginMap origins_;
};

}  // namespace aperture::config
