#pragma once
// What every aperture command shares: the --out/--config/--set options and the rule that a run
// either finishes with status "ok" or leaves summary.json with status "failed" and the error.
#include <CLI/CLI.hpp>
#include <functional>
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

// Runs `body` and writes summary.json: "ok" when it returns, "failed" with the message when it
// throws (the message is also printed as "aperture <command>: error: ..."). Returns the exit code
// (0 or 1).
int RunAndSummarize(const std::string& command_name, output::OutputFolder& out,
                    const std::function<void()>& body);

}  // namespace aperture::apps
