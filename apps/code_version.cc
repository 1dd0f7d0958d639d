#include "apps/code_version.h"

#include "aperture_git_version.h"

namespace aperture::apps {

std::string CodeVersion() { return std::string(APERTURE_VERSION) + " (" APERTURE_GIT_DESCRIBE ")"; }

}  // namespace aperture::apps
