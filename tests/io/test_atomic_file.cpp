// Atomic writes on a full disk (issue 20): /dev/full fails every write with
// ENOSPC, as a full disk does, without root or a small file system.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "io/atomic_file.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

TEST(AtomicFile, WriteBytesReportsAFullDisk) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const std::string data(1 << 16, 'x');
  std::string why;
  EXPECT_FALSE(write_bytes("/dev/full", data.data(), data.size(), why));
  EXPECT_EQ(why, "No space left on device");
}

TEST(AtomicFile, AFailedWriteKeepsTheOldFileNamesTheDestinationAndLeavesNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / ("pt_atomic_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "out.txt").string();
  std::ofstream(path) << "old";
  std::string error;
  // The writer fails as a library naming its temporary file would (OpenEXR does).
  const bool ok = write_atomically(
      path,
      [](const std::string& tmp, std::string& why) {
        std::ofstream(tmp) << "half";
        why = "Failed to write pixel data to image file \"" + tmp + "\"";
        return false;
      },
      error);
  EXPECT_FALSE(ok);
  // The library's message names the destination, not the temporary file.
  EXPECT_EQ(error.rfind("cannot write '" + path + "': Failed to write pixel data to image file \"" + path + "\"", 0), 0u)
      << error;
  EXPECT_EQ(error.find(".tmp-"), std::string::npos) << error;
  std::ifstream in(path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "old");
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.path().filename() == "out.txt" ? 0 : 1;
  EXPECT_EQ(files, 0) << "a temporary file was left";
  // write_text_file goes the same way, and a good write replaces the file whole.
  EXPECT_TRUE(write_text_file(path, "new", error)) << error;
  std::ifstream again(path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(again), {}), "new");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pt
