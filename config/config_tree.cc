#include "config/config_tree.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace aperture::config {
namespace {

std::string Trim(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  const std::size_t end = text.find_last_not_of(" \t");
  return text.substr(begin, end - begin + 1);
}

std::vector<std::string> SplitKey(const std::string& key) {
  std::vector<std::string> segments;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    segments.push_back(key.substr(start, dot - start));
    if (dot == std::string::npos) return segments;
    start = dot + 1;
  }
}

}  // namespace

ConfigTree::ConfigTree() : root_(YAML::NodeType::Map) {}

ConfigTree ConfigTree::FromCommandLine(const std::string& defaults_yaml,
                                       const std::vector<std::string>& config_files,
                                       const std::vector<std::string>& set_items) {
  ConfigTree tree;
  if (!defaults_yaml.empty()) tree.MergeYaml(defaults_yaml, "built-in defaults");
  for (const std::string& file : config_files) tree.MergeFile(file);
  for (const std::string& item : set_items) tree.ApplySet(item);
  return tree;
}

void ConfigTree::MergeYaml(const std::string& yaml_text, const std::string& source) {
  YAML::Node document;
  try {
    document = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(source + ":" + std::to_string(e.mark.line + 1) + ":" +
                                std::to_string(e.mark.column + 1) + ": invalid YAML (" + e.msg +
                                "); fix the syntax of " + source);
  }
  if (document.IsNull()) return;  // an empty file changes nothing
  if (!document.IsMap()) {
    throw std::invalid_argument(source + ": the top level must be a map of sections (key: value), "
                                "got a " + std::string(document.IsSequence() ? "sequence" : "scalar"));
  }
  MergeNode(root_, document, "", ValueOrigin{source, true});
}

void ConfigTree::MergeFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    throw std::runtime_error("cannot read config file '" + path +
                             "'; check the path given to --config");
  }
  std::ostringstream text;
  text << file.rdbuf();
  MergeYaml(text.str(), path);
}

void ConfigTree::ApplySet(const std::string& item) {
  const std::size_t equals = item.find('=');
  if (equals == std::string::npos) {
    throw std::invalid_argument("--set '" + item + "': expected key=value (e.g. gap.roll_deg=30)");
  }
  const std::string key = Trim(item.substr(0, equals));
  const std::vector<std::string> segments = SplitKey(key);
  for (const std::string& segment : segments) {
    if (segment.empty()) {
      throw std::invalid_argument("--set '" + item + "': empty key or key segment in '" + key +
                                  "'; expected dotted.key=value (e.g. gap.roll_deg=30)");
    }
  }
  const std::string value_text = Trim(item.substr(equals + 1));
  YAML::Node value;
  try {
    // An empty value means the empty string, not null: "--set name=" clears a string.
    value = value_text.empty() ? YAML::Node(std::string()) : YAML::Load(value_text);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument("--set '" + item + "': value is not valid YAML (" + e.msg + ")");
  }
  const ValueOrigin origin{"--set " + item, false};
  // Walk/create the parent maps. reset() rebinds the handle; assigning a Node would overwrite the
  // node it refers to (yaml-cpp reference semantics).
  YAML::Node parent;
  parent.reset(root_);
  std::string path;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    path += (path.empty() ? "" : ".") + segments[i];
    YAML::Node child = parent[segments[i]];
    if (!child.IsMap()) {
      parent[segments[i]] = YAML::Node(YAML::NodeType::Map);
      RecordOrigin(path, origin);
      child.reset(parent[segments[i]]);
    }
    parent.reset(child);
  }
  parent[segments.back()] = value;
  RecordOrigin(key, origin);
}

void ConfigTree::MergeNode(YAML::Node destination, const YAML::Node& source,
                           const std::string& path, const ValueOrigin& origin) {
  for (auto it = source.begin(); it != source.end(); ++it) {
    const std::string key = it->first.Scalar();
    const std::string child_path = path.empty() ? key : path + "." + key;
    const YAML::Node existing = static_cast<const YAML::Node&>(destination)[key];
    if (it->second.IsMap() && existing && existing.IsMap()) {
      MergeNode(destination[key], it->second, child_path, origin);
    } else {
      // Key and value nodes are shared (not cloned) so their marks keep pointing into `origin`;
      // re-inserting the key replaces an older layer's key mark too.
      destination.remove(key);
      destination.force_insert(it->first, it->second);
      RecordOrigin(child_path, origin);
    }
  }
}

void ConfigTree::RecordOrigin(const std::string& path, const ValueOrigin& origin) {
  // Drop what older layers recorded below `path`: the whole subtree now comes from `origin`.
  const std::string prefix = path + ".";
  for (auto it = origins_.lower_bound(prefix);
       it != origins_.end() && it->first.compare(0, prefix.size(), prefix) == 0;) {
    it = origins_.erase(it);
  }
  origins_[path] = origin;
}

ParamReader ConfigTree::Reader() const {
  return ParamReader(root_, "", std::make_shared<const OriginMap>(origins_));
}

std::string ConfigTree::ToYaml() const {
  YAML::Emitter emitter;
  emitter << root_;
  return emitter.c_str();
}

}  // namespace aperture::config
