// Subcommands whose machinery has not landed yet. They say what they will do and exit with
// status 3 instead of pretending; each moves to its own file when its issue lands.
#include <iostream>
#include <string>
#include <vector>

#include "apps/commands.h"

namespace aperture::apps {
namespace {

void AddPendingCommand(CLI::App& app, const std::string& name, const std::string& description,
                       const std::string& plan, int* exit_code) {
  auto* command = app.add_subcommand(name, description + " (not available yet)");
  command->allow_extras();
  command->callback([exit_code, name, plan] {
    std::cerr << "aperture " << name << ": not available yet. " << plan << "\n";
    *exit_code = 3;
  });
}

}  // namespace

void AddBenchCommand(CLI::App& app, int* exit_code) {
  AddPendingCommand(app, "bench", "Run perception and control benchmarks against ground truth",
                    "It will run the gap, led and control benchmarks and write summary.json and "
                    "report.html.",
                    exit_code);
}

}  // namespace aperture::apps
