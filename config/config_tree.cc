#include "config/config_tree.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "config/regular_file.h"

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

std::string JsonString(const std::string& text) {
  std::string json = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        json += "\\\"";
        break;
      case '\\':
        json += "\\\\";
        break;
      case '\n':
        json += "\\n";
        break;
      case '\t':
        json += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", c);
          json += escaped;
        } else {
          json += c;
        }
    }
  }
  return json + "\"";
}

std::string JsonScalar(const YAML::Node& node) {
  const std::string& text = node.Scalar();
  // yaml-cpp tags quoted scalars "!": the author meant a string, whatever it looks like.
  if (node.Tag() == "!") return JsonString(text);
  if (text == "true" || text == "false") return text;
  if (text.empty() || text == "null" || text == "~") return "null";
  // Integers exactly, up to the full 64-bit range of a seed (which a double would round); larger
  // ones fall through to the decimal form.
  static const std::regex kInteger(R"([-+]?[0-9]{1,20})");
  if (std::regex_match(text, kInteger)) {
    try {
      return text[0] == '-' ? std::to_string(std::stoll(text)) : std::to_string(std::stoull(text));
    } catch (const std::out_of_range&) {
    }
  }
  static const std::regex kDecimal(R"([-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?)");
  if (std::regex_match(text, kDecimal)) {
    // Re-print so YAML spellings JSON rejects ("+1", ".5", "1.") come out valid.
    const double value = std::strtod(text.c_str(), nullptr);
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.15g", value);
    if (std::strtod(buffer, nullptr) != value) {  // shortest text that reads back exactly
      std::snprintf(buffer, sizeof(buffer), "%.17g", value);
    }
    return buffer;
  }
  return JsonString(text);
}

void AppendJson(const YAML::Node& node, std::string* json) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      *json += '{';
      bool first = true;
      for (auto it = node.begin(); it != node.end(); ++it) {
        *json += (first ? "" : ",") + JsonString(it->first.Scalar()) + ":";
        AppendJson(it->second, json);
        first = false;
      }
      *json += '}';
      return;
    }
    case YAML::NodeType::Sequence:
      *json += '[';
      for (std::size_t i = 0; i < node.size(); ++i) {
        if (i > 0) *json += ',';
        AppendJson(node[i], json);
      }
      *json += ']';
      return;
    case YAML::NodeType::Scalar:
      *json += JsonScalar(node);
      return;
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      *json += "null";
      return;
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
  MergeDocument(document, source);
}

void ConfigTree::MergeDocument(const YAML::Node& document, const std::string& source) {
  if (document.IsNull()) return;  // an empty file changes nothing
  if (!document.IsMap()) {
    throw std::invalid_argument(source +
                                ": the top level must be a map of sections (key: value), "
                                "got a " +
                                std::string(document.IsSequence() ? "sequence" : "scalar"));
  }
  MergeNode(root_, document, "", ValueOrigin{source, true});
}

void ConfigTree::MergeFile(const std::string& path) {
  RequireRegularFileIfPresent(path, "config file");
  std::ifstream file(path);
  if (!file) {
    throw std::runtime_error("cannot read config file '" + path +
                             "'; check the path given to --config");
  }
  std::ostringstream text;
  text << file.rdbuf();
  YAML::Node document;
  try {
    document = YAML::Load(text.str());
  } catch (const YAML::Exception&) {
    MergeYaml(text.str(), path);  // reports the syntax error with its line
    return;
  }
  const YAML::Node& view = document;
  if (view.IsMap() && view["command"] && view["config"] && view["config"].IsMap()) {
    MergeDocument(view["config"], path);  // a summary.json of an earlier run
    return;
  }
  MergeDocument(document, path);
}

void ConfigTree::Put(const std::string& key, const YAML::Node& value, const std::string& source) {
  root_.remove(key);
  root_[key] = value;
  RecordOrigin(key, ValueOrigin{source, false});
}

void ConfigTree::ApplySet(const std::string& item) {
  const std::size_t equals = item.find('=');
  if (equals == std::string::npos) {
    throw UsageError("--set '" + item + "': expected key=value (e.g. gap.roll_deg=30)");
  }
  const std::string key = Trim(item.substr(0, equals));
  const std::vector<std::string> segments = SplitKey(key);
  for (const std::string& segment : segments) {
    if (segment.empty()) {
      throw UsageError("--set '" + item + "': empty key or key segment in '" + key +
                       "'; expected dotted.key=value (e.g. gap.roll_deg=30)");
    }
  }
  const std::string value_text = Trim(item.substr(equals + 1));
  YAML::Node value;
  try {
    // An empty value means the empty string, not null: "--set name=" clears a string.
    value = value_text.empty() ? YAML::Node(std::string()) : YAML::Load(value_text);
  } catch (const YAML::Exception& e) {
    throw UsageError("--set '" + item + "': value is not valid YAML (" + e.msg + ")");
  }
  const ValueOrigin origin{"--set " + item, false, true};
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

std::string ConfigTree::SetItemNamedIn(const std::string& message) const {
  const auto is_key_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.';
  };
  std::string item;
  std::size_t longest = 0;
  for (const auto& [key, origin] : origins_) {
    if (!origin.command_line || key.size() <= longest) continue;
    for (std::size_t at = message.find(key); at != std::string::npos;
         at = message.find(key, at + 1)) {
      const std::size_t end = at + key.size();
      if ((at == 0 || !is_key_char(message[at - 1])) &&
          (end == message.size() || !is_key_char(message[end]) ||
           (message[end] == '.' && (end + 1 == message.size() || message[end + 1] == ' ')))) {
        item = origin.source;
        longest = key.size();
        break;
      }
    }
  }
  return item;
}

ParamReader ConfigTree::Reader() const {
  return ParamReader(root_, "", std::make_shared<const OriginMap>(origins_));
}

std::string ConfigTree::ToYaml() const {
  YAML::Emitter emitter;
  emitter << root_;
  return emitter.c_str();
}

std::string ConfigTree::ToJson() const {
  std::string json;
  AppendJson(root_, &json);
  return json;
}

}  // namespace aperture::config
