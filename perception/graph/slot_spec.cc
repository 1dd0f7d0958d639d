#include "perception/graph/slot_spec.h"

#include <cxxabi.h>

#include <cstdlib>
#include <memory>

namespace aperture::perception {

std::string TypeName(std::type_index type) {
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> demangled(
      abi::__cxa_demangle(type.name(), nullptr, nullptr, &status), std::free);
  return status == 0 && demangled ? std::string(demangled.get()) : std::string(type.name());
}

}  // namespace aperture::perception
