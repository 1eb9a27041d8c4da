// The EXR writer's bytes: a fixed image written with each compression is the
// same file, byte for byte but the time of writing (capDate), as the writer
// before it wrote (tests/data/exr_bytes: OpenImageIO's write_image of every
// channel interleaved into one float buffer, at 9d3cf98), so that writing the
// channels in their file types band by band changed how fast, not what.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "io/image_io.h"
#include "exr_bytes_image.h"

namespace pt {
namespace {

namespace fs = std::filesystem;

// The file's bytes, every capDate attribute's value zeroed.
std::string bytes_without_dates(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string key("capDate\0string\0", 15);
  for (std::size_t at = data.find(key); at != std::string::npos; at = data.find(key, at + 1)) {
    const std::size_t size_at = at + key.size();
    if (size_at + 4 > data.size()) break;
    const auto size = static_cast<std::size_t>(static_cast<unsigned char>(data[size_at])) |
                      static_cast<std::size_t>(static_cast<unsigned char>(data[size_at + 1])) << 8;
    data.replace(size_at + 4, size, size, '\0');
  }
  return data;
}

TEST(ExrBytes, EachCompressionWritesTheBytesOfTheWriterBefore) {
  if (std::string(PT_VERSION) != "0.1.0")
    GTEST_SKIP() << "the golden files name pathtracer 0.1.0 as their Software; this is " PT_VERSION;
  const fs::path dir = fs::temp_directory_path() / ("pt_exr_bytes_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const LayeredImage image = test::exr_bytes_image();
  for (const auto& [name, exr] : {std::pair<std::string, ExrSettings>{"zip", {"zip", false}},
                                  {"none", {"none", false}},
                                  {"piz", {"piz", false}},
                                  {"dwaa", {"dwaa", false}},
                                  {"zip-multipart", {"zip", true}}}) {
    const std::string path = (dir / (name + ".exr")).string(), golden = std::string(PT_TEST_DATA_DIR) + "/data/exr_bytes/" + name + ".exr";
    std::string error;
    ASSERT_TRUE(write_layered_image(path, image, DisplaySettings{}, error, test::exr_bytes_metadata(), exr)) << error;
    const std::string written = bytes_without_dates(path), expected = bytes_without_dates(golden);
    ASSERT_FALSE(expected.empty()) << golden;
    EXPECT_EQ(written.size(), expected.size()) << name;
    EXPECT_TRUE(written == expected) << name << ": the bytes differ from " << golden;
  }
  // With one OpenEXR thread (--threads 1) the bytes are the same.
  ExrSettings one{"zip", false, 1};
  const std::string path = (dir / "zip1.exr").string();
  std::string error;
  ASSERT_TRUE(write_layered_image(path, image, DisplaySettings{}, error, test::exr_bytes_metadata(), one)) << error;
  EXPECT_TRUE(bytes_without_dates(path) == bytes_without_dates(std::string(PT_TEST_DATA_DIR) + "/data/exr_bytes/zip.exr"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pt
