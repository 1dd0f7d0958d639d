// aperture: perception-centric quadrotor autonomy. See README.md for the commands.
#include <iostream>
#include <string>

#include "apps/commands.h"
#include "config/usage_error.h"
#include "output/interruption.h"

namespace {

// A run stopped by SIGINT/SIGTERM (output/interruption.h) after writing its outputs: 128 + the
// signal, as a shell reports a process the signal ended (130 for Ctrl-C, 143 for SIGTERM).
int ExitInterrupted() {
  std::cerr << "aperture: interrupted; the outputs hold what was done until then (summary.json "
               "\"status\": \"interrupted\")\n";
  return aperture::output::InterruptedExitCode();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "aperture: perception-centric quadrotor autonomy (run | sim | render | bench | "
      "calibrate | train | version)"};
  app.require_subcommand(1);
  int exit_code = 0;
  aperture::apps::AddRunCommand(app, &exit_code);
  aperture::apps::AddSimCommand(app, &exit_code);
  aperture::apps::AddRenderCommand(app, &exit_code);
  aperture::apps::AddBenchCommand(app, &exit_code);
  aperture::apps::AddCalibrateCommand(app, &exit_code);
  aperture::apps::AddTrainCommand(app, &exit_code);
  aperture::apps::AddVersionCommand(app, &exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Unknown flags and bad values: the message, a pointer to --help, and exit code 2.
    std::cerr << "aperture: " << e.what() << "\n";
    if (std::string(e.what()).find("subcommand is required") != std::string::npos) {
      // `aperture bench`: name the choices of the deepest command given.
      const CLI::App* command = &app;
      while (!command->get_subcommands().empty()) command = command->get_subcommands().front();
      std::cerr << "Choose one of:\n";
      const std::string prefix = "  aperture " + (command == &app ? "" : command->get_name() + " ");
      for (const CLI::App* choice :
           command->get_subcommands([](const CLI::App*) { return true; })) {
        std::cerr << prefix << choice->get_name() << ": " << choice->get_description() << "\n";
      }
    }
    std::cerr << "Run 'aperture --help' or 'aperture <command> --help' for usage.\n";
    return 2;
  } catch (const aperture::config::UsageError& e) {
    // A mistake in a --set item or an option's value: a usage error like CLI11's, exit code 2.
    std::cerr << "aperture: error: " << e.what() << "\n"
              << "Run 'aperture <command> --help' for usage.\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "aperture: error: " << e.what() << "\n";
    return aperture::output::InterruptionRequested() ? ExitInterrupted() : 1;
  }
  return aperture::output::InterruptionRequested() ? ExitInterrupted() : exit_code;
}
