#include "apps/command_support.h"

namespace aperture::apps {

void AddCommonOptions(CLI::App* command, CommonOptions* options) {
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")
      ->required();
  command->add_option("--config", options->config_files,
                      "YAML parameter file (repeatable; later files win)")
      ->check(CLI::ExistingFile);
  command->add_option("--set", options->set_items,
                      "Parameter override key=value, e.g. image_quality.histogram_bins=32 "
                      "(repeatable; wins over --config)");
}

config::ConfigTree LoadConfig(const CommonOptions& options, const std::string& defaults_yaml) {
  return config::ConfigTree::FromCommandLine(defaults_yaml, options.config_files,
                                             options.set_items);
}

}  // namespace aperture::apps
