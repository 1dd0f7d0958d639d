#include <iostream>

#include "apps/code_version.h"
#include "apps/commands.h"

namespace aperture::apps {

void AddVersionCommand(CLI::App& app, int* exit_code) {
  auto* command = app.add_subcommand("version", "Print the aperture version and its git describe");
  command->callback([exit_code] {
    std::cout << "aperture " << CodeVersion() << "\n";
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
