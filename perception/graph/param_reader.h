#pragma once
// Typed reading of a node's parameters from a key -> value string map (what `--frontends` and
// the YAML config give a front-end factory). Each getter returns the default when the key is
// absent and throws std::invalid_argument naming the owner, key and value when it does not parse.
// CheckAllUsed() then rejects keys no getter asked for (typos), naming them and the known keys.
//
//   ParamReader reader("image_quality", params);
//   params.histogram_bins = reader.Int("histogram_bins", params.histogram_bins);
//   reader.CheckAllUsed();
#include <map>
#include <set>
#include <string>

namespace aperture::perception {

using NodeParams = std::map<std::string, std::string>;

class ParamReader {
 public:
  ParamReader(std::string owner, const NodeParams& params);

  double Double(const std::string& key, double default_value);
  int Int(const std::string& key, int default_value);
  bool Bool(const std::string& key, bool default_value);  // true/false/1/0
  std::string String(const std::string& key, const std::string& default_value);

  void CheckAllUsed() const;

 private:
  // The value of `key` if present (and marks the key as known).
  const std::string* Find(const std::string& key);
  [[noreturn]] void ThrowBadValue(const std::string& key, const std::string& value,
                                  const std::string& expected) const;

  std::string owner_;
  const NodeParams& params_;
  std::set<std::string> known_keys_;
};

}  // namespace aperture::perception
