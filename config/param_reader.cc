#include "config/param_reader.h"

#include <cxxabi.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <regex>
#include <sstream>

namespace aperture::config {
namespace {

std::string Describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return "nothing (null)";
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence:
      return "a sequence of " + std::to_string(node.size()) + " items";
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Undefined:
      break;
  }
  return "nothing";
}

// YAML 1.2 core-schema special floats plus the plain spellings people type on a command line.
bool ParseSpecialDouble(const std::string& text, double* value) {
  static const std::map<std::string, double> kSpecial = {
      {".nan", std::nan("")}, {".NaN", std::nan("")}, {".NAN", std::nan("")}, {"nan", std::nan("")},
      {".inf", HUGE_VAL},     {".Inf", HUGE_VAL},     {".INF", HUGE_VAL},     {"+.inf", HUGE_VAL},
      {"inf", HUGE_VAL},      {"-.inf", -HUGE_VAL},   {"-.Inf", -HUGE_VAL},   {"-.INF", -HUGE_VAL},
      {"-inf", -HUGE_VAL}};
  const auto it = kSpecial.find(text);
  if (it == kSpecial.end()) return false;
  *value = it->second;
  return true;
}

}  // namespace

void ThrowTypeError(const ValueContext& context, const YAML::Node& node,
                    const std::string& expected) {
  const std::string message = context.where + ": key '" + context.key + "' expects " + expected +
                              ", got " + Describe(node) + "; fix the value in " + context.where;
  if (context.command_line) throw UsageError(message);
  throw std::invalid_argument(message);
}

namespace {

// The largest magnitude a number may have, from the unit its key ends in (units are part of the
// names, STYLE.md): an angle in degrees is within one turn either way; any other quantity of this
// project stays below 1e12 in SI units (Unix times in seconds are 1.7e9), so 1e308 is a typo.
struct UnitRange {
  double max_magnitude;
  const char* description;
};

UnitRange RangeOfKey(const std::string& key) {
  std::string name = key.substr(0, key.find('['));  // "rpy_deg[2]": the unit of rpy_deg
  const std::string degrees = "_deg";
  if (name.size() >= degrees.size() &&
      name.compare(name.size() - degrees.size(), degrees.size(), degrees) == 0) {
    return {360.0, "a finite angle in [-360, 360] degrees"};
  }
  return {1e12, "a finite number in [-1e12, 1e12]"};
}

}  // namespace

void ConvertNode(const YAML::Node& node, const ValueContext& context, double* value) {
  const UnitRange range = RangeOfKey(context.key);
  if (!node.IsScalar()) ThrowTypeError(context, node, "a number");
  const std::string& text = node.Scalar();
  double parsed = 0.0;
  if (!ParseSpecialDouble(text, &parsed)) {
    // strtod instead of yaml-cpp's stream parsing: the whole scalar must be a number ("3m" fails).
    char* end = nullptr;
    parsed = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) {
      ThrowTypeError(context, node, "a number");
    }
  }
  // Infinity is a value only where it means "no limit": ReadLimit, or a key whose default is
  // infinite (a dumped configuration reads back). NaN never is.
  const bool infinity_allowed = context.allow_infinite || std::isinf(*value);
  if (std::isinf(parsed) && infinity_allowed) {
    *value = parsed;
    return;
  }
  if (!(std::abs(parsed) <= range.max_magnitude)) {
    ThrowTypeError(context, node,
                   std::string(range.description) + (infinity_allowed ? " or .inf/-.inf" : ""));
  }
  *value = parsed;
}

void ConvertNode(const YAML::Node& node, const ValueContext& context, int* value) {
  if (!node.IsScalar()) ThrowTypeError(context, node, "an integer");
  const std::string& text = node.Scalar();
  char* end = nullptr;
  errno = 0;
  const long parsed = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE ||
      parsed < std::numeric_limits<int>::min() || parsed > std::numeric_limits<int>::max()) {
    ThrowTypeError(context, node, "an integer");
  }
  *value = static_cast<int>(parsed);
}

void ConvertNode(const YAML::Node& node, const ValueContext& context, float* value) {
  double wide = *value;  // the default: infinite allows infinity
  ConvertNode(node, context, &wide);
  if (std::isfinite(wide) && std::abs(wide) > std::numeric_limits<float>::max()) {
    ThrowTypeError(context, node, "a number within single-precision range");
  }
  *value = static_cast<float>(wide);
}

namespace {

unsigned long long ParseUnsigned(const YAML::Node& node, const ValueContext& context,
                                 unsigned long long max) {
  const std::string expected = "a non-negative integer up to " + std::to_string(max);
  if (!node.IsScalar()) ThrowTypeError(context, node, expected);
  const std::string& text = node.Scalar();
  // strtoull silently negates "-1"; only digits are accepted.
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    ThrowTypeError(context, node, expected);
  }
  errno = 0;
  const unsigned long long parsed = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE || parsed > max) ThrowTypeError(context, node, expected);
  return parsed;
}

}  // namespace

void ConvertNode(const YAML::Node& node, const ValueContext& context, unsigned int* value) {
  *value = static_cast<unsigned int>(
      ParseUnsigned(node, context, std::numeric_limits<unsigned int>::max()));
}

void ConvertNode(const YAML::Node& node, const ValueContext& context, unsigned long* value) {
  *value = static_cast<unsigned long>(
      ParseUnsigned(node, context, std::numeric_limits<unsigned long>::max()));
}

void ConvertNode(const YAML::Node& node, const ValueContext& context, bool* value) {
  // YAML 1.2 core schema booleans only: "yes"/"on" are strings there, so they are rejected rather
  // than silently meaning true.
  if (node.IsScalar()) {
    const std::string& text = node.Scalar();
    if (text == "true" || text == "True" || text == "TRUE") {
      *value = true;
      return;
    }
    if (text == "false" || text == "False" || text == "FALSE") {
      *value = false;
      return;
    }
  }
  ThrowTypeError(context, node, "a boolean (true or false)");
}

void ConvertNode(const YAML::Node& node, const ValueContext& context, std::string* value) {
  if (!node.IsScalar()) ThrowTypeError(context, node, "a string");
  *value = node.Scalar();
}

void ConvertNode(const YAML::Node& node, const ValueContext& context, Eigen::VectorXd* value) {
  std::vector<double> numbers;
  ConvertNode(node, context, &numbers);
  *value =
      Eigen::Map<const Eigen::VectorXd>(numbers.data(), static_cast<Eigen::Index>(numbers.size()));
}

ParamReader::ParamReader(YAML::Node node, std::string path,
                         std::shared_ptr<const OriginMap> origins)
    : node_(std::move(node)),
      path_(std::move(path)),
      origins_(std::move(origins)),
      section_types_(std::make_shared<std::map<std::string, std::set<std::string>>>()) {
  if (node_ && !node_.IsMap() && !node_.IsNull()) {
    const std::string where = Locate(path_, node_.Mark());
    throw std::invalid_argument(where + ": '" + (path_.empty() ? "<document root>" : path_) +
                                "' must be a map of key: value entries, got " + Describe(node_));
  }
}

ParamReader::ParamReader(YAML::Node node, const std::string& source)
    : ParamReader(std::move(node), "",
                  std::make_shared<const OriginMap>(OriginMap{{"", ValueOrigin{source, true}}})) {}

std::string ParamReader::FullKey(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool ParamReader::Has(const std::string& key) const {
  return node_.IsMap() && static_cast<bool>(static_cast<const YAML::Node&>(node_)[key]);
}

std::vector<std::string> ParamReader::Keys() const {
  std::vector<std::string> keys;
  if (!node_.IsMap()) return keys;
  for (auto it = node_.begin(); it != node_.end(); ++it) keys.push_back(it->first.Scalar());
  return keys;
}

YAML::Node ParamReader::Lookup(const std::string& key) {
  known_keys_.insert(key);
  if (!node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  // Const access: non-const operator[] would insert the key into the shared tree. A missing key
  // yields an invalid handle; hand out a plain undefined node instead.
  const YAML::Node found = static_cast<const YAML::Node&>(node_)[key];
  return found ? found : YAML::Node(YAML::NodeType::Undefined);
}

ParamReader ParamReader::Section(const std::string& key) {
  ParamReader section(Lookup(key), FullKey(key), origins_);
  section.section_types_ = section_types_;
  return section;
}

const ValueOrigin* ParamReader::OriginOf(const std::string& full_key) const {
  // The longest recorded prefix of the dotted key names the source.
  std::string prefix = full_key;
  while (true) {
    const auto it = origins_->find(prefix);
    if (it != origins_->end()) return &it->second;
    if (prefix.empty()) return nullptr;
    const std::size_t dot = prefix.rfind('.');
    prefix = dot == std::string::npos ? "" : prefix.substr(0, dot);
  }
}

std::string ParamReader::Locate(const std::string& full_key, const YAML::Mark& mark) const {
  const ValueOrigin* origin = OriginOf(full_key);
  if (origin == nullptr) return "<unknown source>";
  if (origin->has_lines && !mark.is_null()) {
    return origin->source + ":" + std::to_string(mark.line + 1) + ":" +
           std::to_string(mark.column + 1);
  }
  return origin->source;
}

ValueContext ParamReader::ContextOf(const std::string& key, const YAML::Node& child) const {
  const ValueOrigin* origin = OriginOf(FullKey(key));
  return ValueContext{Locate(FullKey(key), child.Mark()), FullKey(key),
                      origin != nullptr && origin->command_line};
}

void ParamReader::ReadLimit(const std::string& key, double* value) {
  const YAML::Node child = Lookup(key);
  if (!child) return;
  ValueContext context = ContextOf(key, child);
  context.allow_infinite = true;
  ConvertNode(child, context, value);
}

void ParamReader::Fail(const std::string& key, const std::string& what) const {
  const std::string message = Where(key) + ": '" + FullKey(key) + "' " + what;
  const ValueOrigin* origin = OriginOf(FullKey(key));
  if (origin != nullptr && origin->command_line) throw UsageError(message);
  throw std::invalid_argument(message);
}

std::string ParamReader::CommandLineItemsInside() const {
  std::string items;
  const std::string prefix = path_.empty() ? "" : path_ + ".";
  for (auto it = origins_->lower_bound(prefix);
       it != origins_->end() && it->first.compare(0, prefix.size(), prefix) == 0; ++it) {
    if (it->second.command_line && items.find(it->second.source) == std::string::npos) {
      items += (items.empty() ? "" : ", ") + it->second.source;
    }
  }
  return items;
}

void ParamReader::RejectEntriesCreatedBySet(const std::string& entry_kind,
                                            const std::string& declaring_key) const {
  if (!node_.IsMap()) return;
  // An entry --set created, and whether its items declare it through `declaring_key`.
  const auto created_by_set = [&](const YAML::Node& name) {
    const auto origin = origins_->find(FullKey(name.Scalar()));
    return origin != origins_->end() && origin->second.command_line;
  };
  const auto declared = [&](const YAML::Node& entry) {
    return !declaring_key.empty() && entry.IsMap() &&
           static_cast<bool>(static_cast<const YAML::Node&>(entry)[declaring_key]);
  };
  std::string known;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!created_by_set(it->first) || declared(it->second)) {
      known += (known.empty() ? "" : ", ") + it->first.Scalar();
    }
  }
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!created_by_set(it->first) || declared(it->second)) continue;
    const std::string name = it->first.Scalar();
    const std::string how_to_add =
        declaring_key.empty()
            ? "add a new " + entry_kind + " in a --config file (--set only changes existing ones)"
            : "declare a new " + entry_kind + " by its " + declaring_key + " (--set " +
                  FullKey(name) + "." + declaring_key + "=...) or in a --config file";
    throw UsageError(origins_->at(FullKey(name)).source + ": unknown " + entry_kind + " '" + name +
                     "' in '" + path_ +
                     "'; known: " + (known.empty() ? std::string("(none)") : known) +
                     ". Fix the spelling, or " + how_to_add + ".");
  }
}

namespace {

// "aperture::planning::GapMissionParams" -> "GapMissionParams": the name a message names it by.
std::string ShortTypeName(const std::type_info& type) {
  int status = 0;
  char* demangled = abi::__cxa_demangle(type.name(), nullptr, nullptr, &status);
  std::string name = status == 0 && demangled != nullptr ? demangled : type.name();
  std::free(demangled);
  const std::size_t colons = name.rfind("::");
  return colons == std::string::npos ? name : name.substr(colons + 2);
}

}  // namespace

void ParamReader::NoteSectionType(const std::type_info& type) const {
  (*section_types_)[ShortTypeName(type)].insert(path_);
}

void ParamReader::FailValidation(const std::type_info& type, const std::string& what) const {
  // The key path of the section a struct named in the message was loaded from: this section for
  // its own struct, else the one section of that struct inside this one (or in the whole tree);
  // this section too for a struct of its values checked together (a field this section reads).
  const std::string own_type = ShortTypeName(type);
  const auto section_of = [&](const std::string& type_name,
                              const std::string& field) -> std::optional<std::string> {
    if (type_name == own_type) return path_;
    const auto found = section_types_->find(type_name);
    if (found == section_types_->end()) {
      if (known_keys_.count(field) > 0) return path_;
      return std::nullopt;
    }
    std::vector<std::string> inside;
    for (const std::string& section : found->second) {
      if (path_.empty() || section.compare(0, path_.size() + 1, path_ + ".") == 0) {
        inside.push_back(section);
      }
    }
    if (inside.size() == 1) return inside.front();
    if (inside.empty() && found->second.size() == 1) return *found->second.begin();
    return std::nullopt;  // ambiguous: keep the struct's name
  };
  // "GapMissionParams.hover_s = -1 ..." and "TraverseParameters: max_evaluations = 0 ...".
  static const std::regex kQualifiedField(
      R"(\b([A-Z][A-Za-z0-9]*)(?:\.([A-Za-z_][A-Za-z0-9_]*)|: ([A-Za-z_][A-Za-z0-9_]*)(?= =)))");
  std::string message;
  std::string first_key;  // full key path of the first field named
  auto rest = what.cbegin();
  for (std::sregex_iterator it(what.begin(), what.end(), kQualifiedField), end; it != end; ++it) {
    const std::smatch& match = *it;
    const std::string field = match[2].matched ? match[2].str() : match[3].str();
    const std::optional<std::string> section = section_of(match[1].str(), field);
    if (!section) continue;
    const std::string key = section->empty() ? field : *section + "." + field;
    if (first_key.empty()) first_key = key;
    message.append(rest, match[0].first);
    message += key;
    rest = match[0].second;
  }
  message.append(rest, what.cend());

  // Where the named value came from (its file:line:column or --set item) when it is in the tree
  // under this section; else where this section came from.
  std::string where;
  const std::string prefix = path_.empty() ? "" : path_ + ".";
  if (!first_key.empty() && first_key.compare(0, prefix.size(), prefix) == 0) {
    // reset() rebinds a handle; assigning one Node to another would overwrite the tree.
    YAML::Node value;
    value.reset(node_);
    const std::string relative = first_key.substr(prefix.size());
    for (std::size_t start = 0; value.IsMap();) {
      const std::size_t dot = relative.find('.', start);
      const YAML::Node child =
          static_cast<const YAML::Node&>(value)[relative.substr(start, dot - start)];
      if (!child) break;
      if (dot == std::string::npos) {
        where = Locate(first_key, child.Mark());
        break;
      }
      value.reset(child);
      start = dot + 1;
    }
  }
  // A --set item inside the section makes it a usage error, named unless it is the location.
  const std::string items = CommandLineItemsInside();
  std::vector<std::string> notes;
  if (where.empty()) {
    where = Where("");
    if (!path_.empty()) notes.push_back("section '" + path_ + "'");
  }
  if (!items.empty() && items.find(where) == std::string::npos) {
    notes.push_back("set on the command line: " + items);
  }
  for (std::size_t i = 0; i < notes.size(); ++i) {
    where += (i == 0 ? " (" : "; ") + notes[i] + (i + 1 == notes.size() ? ")" : "");
  }
  if (!items.empty()) throw UsageError(where + ": " + message);
  throw std::invalid_argument(where + ": " + message);
}

std::string ParamReader::Where(const std::string& key) const {
  const YAML::Node child =
      node_.IsMap() ? static_cast<const YAML::Node&>(node_)[key] : YAML::Node();
  return Locate(FullKey(key), child ? child.Mark() : node_.Mark());
}

void ParamReader::RejectUnknownKeys() const {
  if (!node_.IsMap()) return;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (known_keys_.count(key) > 0) continue;
    std::ostringstream known;
    for (const std::string& name : known_keys_) {
      known << (known.tellp() > 0 ? ", " : "") << name;
    }
    const std::string message =
        Locate(FullKey(key), it->first.Mark()) + ": unknown key '" + FullKey(key) + "'" +
        (path_.empty() ? "" : " in section '" + path_ + "'") +
        "; known keys: " + (known_keys_.empty() ? std::string("(none)") : known.str()) +
        ". Fix the spelling or remove it.";
    const ValueOrigin* origin = OriginOf(FullKey(key));
    if (origin != nullptr && origin->command_line) throw UsageError(message);
    throw std::invalid_argument(message);
  }
}

}  // namespace aperture::config
