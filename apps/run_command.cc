#include <iostream>

#include "apps/commands.h"

namespace aperture::apps {

void AddRunCommand(CLI::App& app, int* exit_code) {
  auto* command = app.add_subcommand("run", "Run perception front ends on a camera or sequence");
  command->allow_extras();
  command->callback([exit_code] {
    std::cerr << "aperture run: not available yet.\n";
    *exit_code = 3;
  });
}

void AddCalibrateCommand(CLI::App& app, int* exit_code) {
  auto* command = app.add_subcommand("calibrate", "Calibrate a camera from pattern images");
  command->allow_extras();
  command->callback([exit_code] {
    std::cerr << "aperture calibrate: not available yet.\n";
    *exit_code = 3;
  });
}

}  // namespace aperture::apps
