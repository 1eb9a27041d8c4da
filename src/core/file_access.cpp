#include "core/file_access.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>

namespace pt {

std::string why_not_read(const std::string& path, std::uintmax_t max_bytes, const std::string& kind) {
  if (const std::string why = why_unreadable(path); !why.empty()) return "cannot read the file: " + why;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return "cannot read the file: " + ec.message();
  if (size > max_bytes)
    return "the file is " + std::to_string(size) + " bytes; " + kind + " files over " + std::to_string(max_bytes) +
           " bytes are refused";
  return {};
}

std::string special_file_kind(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    return errno == ELOOP ? "it is a symbolic link loop (too many levels of symbolic links)" : std::string();
  if (S_ISREG(st.st_mode)) return {};
  if (S_ISDIR(st.st_mode)) return "it is a directory, not a file";
  if (S_ISFIFO(st.st_mode)) return "it is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(st.st_mode)) return "it is a character device, not a regular file";
  if (S_ISBLK(st.st_mode)) return "it is a block device, not a regular file";
  if (S_ISSOCK(st.st_mode)) return "it is a socket, not a regular file";
  return "it is not a regular file";
}

std::string why_unreadable(const std::string& path) {
  if (std::string kind = special_file_kind(path); !kind.empty()) return kind;
  // O_NONBLOCK: should the path become a FIFO after the check, open() does
  // not wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return std::error_code(errno, std::generic_category()).message();
  ::close(fd);
  return {};
}

}  // namespace pt
