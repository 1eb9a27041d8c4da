// MappedFile: a file's bytes mapped read-only (the merge's shard files).
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/mapped_file.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

class MappedFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pt_mapped_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  fs::path dir_;
};

TEST_F(MappedFileTest, MapsTheFilesBytes) {
  std::string bytes(100000, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7 + 3);
  std::string error;
  std::optional<MappedFile> file = MappedFile::open(write("a.bin", bytes), error);
  ASSERT_TRUE(file) << error;
  EXPECT_EQ(file->bytes(), bytes);
  MappedFile moved = std::move(*file);  // the mapping moves with it
  EXPECT_EQ(moved.bytes(), bytes);
  EXPECT_TRUE(file->bytes().empty());
  std::optional<MappedFile> empty = MappedFile::open(write("empty.bin", ""), error);
  ASSERT_TRUE(empty) << error;
  EXPECT_TRUE(empty->bytes().empty());
}

TEST_F(MappedFileTest, RefusesWhatIsNoReadableFile) {
  std::string error;
  EXPECT_FALSE(MappedFile::open((dir_ / "missing.bin").string(), error));
  EXPECT_EQ(error, "No such file or directory");
  EXPECT_FALSE(MappedFile::open(dir_.string(), error));
  EXPECT_NE(error.find("directory"), std::string::npos) << error;
  const std::string fifo = (dir_ / "fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_FALSE(MappedFile::open(fifo, error));  // refused at once, not blocked on a writer
  EXPECT_NE(error.find("FIFO"), std::string::npos) << error;
}

}  // namespace
}  // namespace pt
