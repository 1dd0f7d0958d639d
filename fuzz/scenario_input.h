#pragma once
// The scenario fuzzers' input: a first line naming a built-in scenario (gap, gapflyt, led, tags,
// forest) makes its YAML the defaults, as `aperture sim NAME` / `aperture render NAME` start
// from; the rest is the fuzzed text. Without a built-in name the whole input is fuzzed text on
// empty defaults.
#include <string>
#include <vector>

#include "sim/scenario/scenario.h"

namespace aperture::fuzz {

struct ScenarioInput {
  std::string defaults_yaml;
  std::string text;
};

inline ScenarioInput SplitScenarioInput(const std::string& input) {
  const std::size_t end = input.find('\n');
  const std::string first_line = input.substr(0, end);
  for (const std::string& name : sim::BuiltinScenarioNames()) {
    if (first_line == name) {
      return {sim::BuiltinScenarioYaml(name),
              end == std::string::npos ? "" : input.substr(end + 1)};
    }
  }
  return {"", input};
}

}  // namespace aperture::fuzz
