#pragma once
// The check every reader of a user's file makes before opening it: a path that exists but is a
// device, FIFO or socket is not "missing" — reading a FIFO would wait forever, /dev/null reads as
// an empty file. Readers keep their own "cannot be opened" message for a missing path.
#include <string>

namespace aperture::config {

// Throws std::invalid_argument "<what> '<path>' is not a regular file (a device, FIFO or socket);
// give a file" when `path` exists and is not a regular file (or a link to one).
void RequireRegularFileIfPresent(const std::string& path, const std::string& what);

}  // namespace aperture::config
