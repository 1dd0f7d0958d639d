#pragma once
// What every aperture command shares: the --out/--config/--set options. Commands run their body
// through output::RunAndWriteSummary, so a run either finishes with status "ok" or leaves
// summary.json with status "failed" and the error (which main() prints, exiting with 1).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "config/config_tree.h"
#include "output/output_folder.h"

namespace aperture::apps {

struct CommonOptions {
  std::string out_dir;
  std::vector<std::string> config_files;  // --config FILE (repeatable, in order)
  std::vector<std::string> set_items;     // --set key=value (repeatable, in order)
};

// Adds --out (required), --config and --set to `command`.
void AddCommonOptions(CLI::App* command, CommonOptions* options);

// The effective configuration: built-in `defaults_yaml` < --config files < --set items.
config::ConfigTree LoadConfig(const CommonOptions& options, const std::string& defaults_yaml);

}  // namespace aperture::apps
