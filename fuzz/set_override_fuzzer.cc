// `--set key=value` overrides (config/config_tree.h ApplySet), one per line after the first line
// (a built-in scenario, see scenario_input.h), then the strict scenario load the commands do.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/config_tree.h"
#include "fuzz/scenario_input.h"
#include "fuzz/yaml_exception_guard.h"
#include "sim/scenario/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const aperture::fuzz::ScenarioInput input =
      aperture::fuzz::SplitScenarioInput(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<std::string> set_items;
  std::istringstream lines(input.text);
  for (std::string line; std::getline(lines, line);) set_items.push_back(line);
  try {
    aperture::config::ConfigTree tree =
        aperture::config::ConfigTree::FromCommandLine(input.defaults_yaml, {}, set_items);
    aperture::sim::LoadScenarioParams(tree);
    tree.ToJson();  // summary.json's "config"
  } catch (const YAML::Exception& e) {
    aperture::fuzz::AbortOnLeakedYamlException(e);
  } catch (const std::invalid_argument&) {  // config::UsageError included
  } catch (const std::runtime_error&) {     // a referenced file (e.g. leds.config) that is missing
  }
  return 0;
}
