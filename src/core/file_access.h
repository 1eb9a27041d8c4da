// Whether a file can be opened for reading, and if not why, in the system's
// words. The readers (PLY, OBJ, textures) ask first, so that an unreadable
// file is reported as such ("Permission denied") rather than as a file their
// libraries could not open.
#pragma once

#include <string>

namespace pt {

// Why `path` cannot be opened for reading ("Permission denied", "No such file
// or directory", ...), or an empty string if it can.
std::string why_unreadable(const std::string& path);

}  // namespace pt
