#include "perception/graph/param_reader.h"

#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace aperture::perception {

ParamReader::ParamReader(std::string owner, const NodeParams& params)
    : owner_(std::move(owner)), params_(params) {}

const std::string* ParamReader::Find(const std::string& key) {
  known_keys_.insert(key);
  const auto it = params_.find(key);
  return it == params_.end() ? nullptr : &it->second;
}

void ParamReader::ThrowBadValue(const std::string& key, const std::string& value,
                                const std::string& expected) const {
  throw std::invalid_argument(owner_ + ": parameter '" + key + "' = '" + value + "' is not " +
                              expected);
}

double ParamReader::Double(const std::string& key, double default_value) {
  const std::string* value = Find(key);
  if (value == nullptr) return default_value;
  std::size_t used = 0;
  try {
    const double parsed = std::stod(*value, &used);
    if (used == value->size()) return parsed;
  } catch (const std::exception&) {
  }
  ThrowBadValue(key, *value, "a number");
}

int ParamReader::Int(const std::string& key, int default_value) {
  const std::string* value = Find(key);
  if (value == nullptr) return default_value;
  std::size_t used = 0;
  try {
    const int parsed = std::stoi(*value, &used);
    if (used == value->size()) return parsed;
  } catch (const std::exception&) {
  }
  ThrowBadValue(key, *value, "an integer");
}

bool ParamReader::Bool(const std::string& key, bool default_value) {
  const std::string* value = Find(key);
  if (value == nullptr) return default_value;
  if (*value == "true" || *value == "1") return true;
  if (*value == "false" || *value == "0") return false;
  ThrowBadValue(key, *value, "a boolean (true/false/1/0)");
}

std::string ParamReader::String(const std::string& key, const std::string& default_value) {
  const std::string* value = Find(key);
  return value == nullptr ? default_value : *value;
}

void ParamReader::CheckAllUsed() const {
  std::ostringstream unknown;
  for (const auto& [key, value] : params_) {
    if (known_keys_.count(key) == 0) unknown << " '" << key << "'";
  }
  if (unknown.str().empty()) return;
  std::ostringstream message;
  message << owner_ << ": unknown parameter(s)" << unknown.str() << "; known parameters:";
  for (const std::string& key : known_keys_) message << " '" << key << "'";
  throw std::invalid_argument(message.str());
}

}  // namespace aperture::perception
