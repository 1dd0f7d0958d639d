// LED configuration files (`leds: [[x, y, z], ...]`, perception/led/led_configuration.h), as
// `aperture run --leds FILE` and the led scenario read them, validation included.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

#include "perception/led/led_configuration.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream yaml(std::string(reinterpret_cast<const char*>(data), size));
  try {
    aperture::perception::LedConfiguration::Parse(yaml, "fuzz-leds.yaml");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
