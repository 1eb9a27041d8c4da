// Whether a file can be opened for reading, and if not why, in the system's
// words. The readers (scene, PLY, OBJ, textures, the environment map,
// checkpoints) ask first, so that an unreadable file is reported as such
// ("Permission denied") rather than as a file their libraries could not open,
// and so that nothing opens a FIFO (which blocks until a writer comes) or
// reads a device such as /dev/zero (which never ends).
#pragma once

#include <cstdint>
#include <string>

namespace pt {

// Why `path` cannot be read as a file, or an empty string if it can: the
// system's words ("Permission denied", "No such file or directory"), or what
// it is when it is no regular file ("it is a FIFO (named pipe), not a regular
// file", "it is a character device, not a regular file", "it is a directory, not a
// file", "it is a symbolic link loop (too many levels of symbolic links)").
std::string why_unreadable(const std::string& path);

// why_unreadable, or if the file is larger than `max_bytes`, that it is
// refused ("the file is N bytes; `kind` files over M bytes are refused"); the
// readable answer is prefixed "cannot read the file: ". Empty if it can be read.
std::string why_not_read(const std::string& path, std::uintmax_t max_bytes, const std::string& kind);

// What kind of entry `path` is when it exists but is no regular file (the
// phrases above), or an empty string (a regular file, or nothing there).
std::string special_file_kind(const std::string& path);

}  // namespace pt
