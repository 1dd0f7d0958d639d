#pragma once
// The version of this build: the project version and the source tree's git describe, e.g.
// "0.1.0 (64c6630a1b2c-dirty)". `aperture version` prints it; bench shards record it and
// `aperture bench merge` merges only shards of one code version (a "-dirty" tree is one version
// whatever its uncommitted edits: commit before running shards on several machines).
#include <string>

namespace aperture::apps {

std::string CodeVersion();

}  // namespace aperture::apps
