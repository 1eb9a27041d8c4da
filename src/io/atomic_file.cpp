#include "io/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace pt {

bool write_atomically(const std::string& path,
                      const std::function<bool(const std::string& tmp_path, std::string& why)>& write,
                      std::string& error) {
  const std::string tmp = path + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
  std::string why;
  bool ok = write(tmp, why);
  if (ok && std::rename(tmp.c_str(), path.c_str()) != 0) {
    why = std::strerror(errno);
    ok = false;
  }
  if (!ok) {
    std::remove(tmp.c_str());
    error = "cannot write '" + path + "': " + (why.empty() ? std::string("unknown error") : why);
  }
  return ok;
}

bool write_text_file(const std::string& path, const std::string& text, std::string& error) {
  return write_atomically(
      path,
      [&](const std::string& tmp, std::string& why) {
        std::ofstream f(tmp, std::ios::binary);
        if (!f) {
          why = std::strerror(errno);
          return false;
        }
        f << text;
        f.close();
        if (!f) why = "write failed";
        return static_cast<bool>(f);
      },
      error);
}

}  // namespace pt
