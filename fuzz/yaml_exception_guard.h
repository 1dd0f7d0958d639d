#pragma once
// yaml-cpp's exceptions derive from std::runtime_error, which some parsers throw on purpose (an
// unreadable file). One that escapes a parser is a finding (its message names no file or key):
// the fuzzers catch it first and abort.
#include <yaml-cpp/exceptions.h>

#include <cstdio>
#include <cstdlib>

namespace aperture::fuzz {

[[noreturn]] inline void AbortOnLeakedYamlException(const YAML::Exception& e) {
  std::fprintf(stderr, "yaml-cpp exception escaped the parser: %s\n", e.what());
  std::abort();
}

}  // namespace aperture::fuzz
