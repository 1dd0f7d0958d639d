#include <iostream>

#include "apps/commands.h"

namespace aperture::apps {

void AddVersionCommand(CLI::App& app, int* exit_code) {
  auto* command = app.add_subcommand("version", "Print the aperture version");
  command->callback([exit_code] {
    std::cout << "aperture " << APERTURE_VERSION << "\n";
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
