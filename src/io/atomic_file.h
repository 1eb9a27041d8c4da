// Atomic file output: the content is written to a temporary file in the
// destination's folder and renamed over the destination only once complete,
// so a failed or killed run never leaves a partial file at `path`, and an
// existing file is replaced whole. Every write, flush and close is checked: a
// full disk (ENOSPC) or a file size limit (EFBIG) fails the write with the
// system's words, the temporary file is removed and the old file stays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace pt {

// `write(tmp_path, why)` writes the whole content to tmp_path and returns true,
// or sets `why` and returns false. On failure nothing is left behind and
// `error` says "cannot write '<path>': <why>".
bool write_atomically(const std::string& path,
                      const std::function<bool(const std::string& tmp_path, std::string& why)>& write,
                      std::string& error);

// Writes `size` bytes to the new file `path` (created or truncated), checking
// every write() and the close(); false with `why` (strerror: "No space left on
// device", "File too large"). For the inside of a write_atomically callback.
bool write_bytes(const std::string& path, const void* data, std::size_t size, std::string& why);

// Writes all `size` bytes to the open file `fd`, handing write() at most
// `piece` bytes at a time and retrying after EINTR; false with `why`
// (strerror, or "the disk accepted no more bytes"). Does not close `fd`.
bool write_fd(int fd, const void* data, std::size_t size, std::string& why, std::size_t piece = SIZE_MAX);

// Why a stream write failed: "write failed: <strerror(errno)>" when the
// system said why, else "write failed".
std::string stream_write_error();

// Writes `text` to `path` atomically.
bool write_text_file(const std::string& path, const std::string& text, std::string& error);

}  // namespace pt
