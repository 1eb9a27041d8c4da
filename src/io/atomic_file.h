// Atomic file output: the content is written to a temporary file in the
// destination's folder and renamed over the destination only once complete,
// so a failed or killed run never leaves a partial file at `path`, and an
// existing file is replaced whole.
#pragma once

#include <functional>
#include <string>

namespace pt {

// `write(tmp_path, why)` writes the whole content to tmp_path and returns true,
// or sets `why` and returns false. On failure nothing is left behind and
// `error` says "cannot write '<path>': <why>".
bool write_atomically(const std::string& path,
                      const std::function<bool(const std::string& tmp_path, std::string& why)>& write,
                      std::string& error);

// Writes `text` to `path` atomically.
bool write_text_file(const std::string& path, const std::string& text, std::string& error);

}  // namespace pt
