#include "render/textures/scratch_folder.h"

#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace pt {

ScratchFolder::~ScratchFolder() {
  if (path_.empty()) return;
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);  // nothing to report to from a destructor
}

std::string ScratchFolder::write(const std::vector<unsigned char>& bytes, const std::string& extension,
                                 std::string& error) {
  if (path_.empty()) {
    std::error_code ec;
    std::string pattern = (std::filesystem::temp_directory_path(ec) / "pathtracer-XXXXXX").string();
    if (ec) pattern = "/tmp/pathtracer-XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr) {
      error = "cannot create a temporary folder for embedded images: " + std::string(std::strerror(errno));
      return {};
    }
    path_ = pattern;  // mkdtemp creates it with mode 0700
  }
  const std::string file = path_ + "/image-" + std::to_string(files_++) + "." + extension;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    error = "cannot write the embedded image to '" + file + "'";
    return {};
  }
  return file;
}

}  // namespace pt
