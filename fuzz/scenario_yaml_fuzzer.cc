// Scenario YAML (sim/scenario/scenario_params.h), as `aperture sim NAME --config FILE` and
// `aperture render NAME --config FILE` load it: a built-in scenario's defaults (first line, see
// scenario_input.h) < the fuzzed file, then the strict load with every section's validation.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "config/config_tree.h"
#include "fuzz/scenario_input.h"
#include "fuzz/yaml_exception_guard.h"
#include "sim/scenario/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const aperture::fuzz::ScenarioInput input =
      aperture::fuzz::SplitScenarioInput(std::string(reinterpret_cast<const char*>(data), size));
  try {
    aperture::config::ConfigTree tree;
    if (!input.defaults_yaml.empty()) tree.MergeYaml(input.defaults_yaml, "built-in defaults");
    tree.MergeYaml(input.text, "fuzz-scenario.yaml");
    aperture::sim::LoadScenarioParams(tree);
    tree.ToJson();  // summary.json's "config"
  } catch (const YAML::Exception& e) {
    aperture::fuzz::AbortOnLeakedYamlException(e);
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {  // a referenced file (e.g. leds.config) that is missing
  }
  return 0;
}
