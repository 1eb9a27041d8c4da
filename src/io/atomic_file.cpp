#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace pt {

bool write_atomically(const std::string& path,
                      const std::function<bool(const std::string& tmp_path, std::string& why)>& write,
                      std::string& error) {
  const std::string tmp = path + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
  std::string why;
  errno = 0;
  bool ok = write(tmp, why);
  const int write_errno = errno;
  if (ok && std::rename(tmp.c_str(), path.c_str()) != 0) {
    why = std::strerror(errno);
    ok = false;
  }
  if (!ok) {
    std::remove(tmp.c_str());
    if (why.empty()) why = "unknown error";
    // Libraries name the file they were given, the temporary one: the user
    // knows only `path`. And some (OpenEXR: "File output failed.") do not say
    // what the system said.
    for (std::size_t at = why.find(tmp); at != std::string::npos; at = why.find(tmp, at + path.size()))
      why.replace(at, tmp.size(), path);
    const std::string system = write_errno != 0 ? std::strerror(write_errno) : "";
    if (!system.empty() && why.find(system) == std::string::npos) why += " (" + system + ")";
    error = "cannot write '" + path + "': " + why;
  }
  return ok;
}

bool write_fd(int fd, const void* data, std::size_t size, std::string& why, std::size_t piece) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, std::min(size, piece));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      why = n < 0 ? std::strerror(errno) : "the disk accepted no more bytes";
      return false;
    }
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool write_bytes(const std::string& path, const void* data, std::size_t size, std::string& why) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    why = std::strerror(errno);
    return false;
  }
  if (!write_fd(fd, data, size, why)) {
    ::close(fd);
    return false;
  }
  if (::close(fd) != 0) {  // e.g. a delayed write error on a network file system
    why = std::strerror(errno);
    return false;
  }
  return true;
}

std::string stream_write_error() {
  return errno != 0 ? "write failed: " + std::string(std::strerror(errno)) : std::string("write failed");
}

bool write_text_file(const std::string& path, const std::string& text, std::string& error) {
  return write_atomically(
      path, [&](const std::string& tmp, std::string& why) { return write_bytes(tmp, text.data(), text.size(), why); },
      error);
}

}  // namespace pt
