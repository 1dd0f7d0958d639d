#pragma once
// UsageError: a mistake on the command line (a `--set` item, an option's value), as opposed to
// bad data in a file. main() prints both; a UsageError exits with 2 like CLI11's own parse errors,
// bad data with 1 (docs/usage.md, "Exit codes").
#include <stdexcept>

namespace aperture::config {

class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace aperture::config
