#include "io/exr_uncompressed.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <set>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "imagelib/image_library.h"
#include "io/atomic_file.h"
#include "io/exr_pack.h"

namespace pt {

static_assert(std::endian::native == std::endian::little, "EXR files are little-endian, as this machine");

namespace {

// OpenEXR's limits and flags (OpenEXR's file layout, "Version Field").
constexpr int kMaxNameLength = 255;       // of an attribute's or channel's name
constexpr std::size_t kLongName = 32;     // names this long set the long-names flag
constexpr uint32_t kVersion = 2, kLongNamesFlag = 0x400;
constexpr int kHalf = 1, kFloat = 2;      // OpenEXR's pixel types
// The file is handed to the system this many bytes at a time: writes of 8 MiB
// took the kernel ~1.3 s for the 447 MiB of a 1080p merge with every AOV,
// pieces of 64 to 430 KiB (OpenEXR's own writes are up to 420 KiB) ~0.35 s
// (Linux 6.x, ext4; docs/bench/merge-s15.md).
constexpr std::size_t kWritePiece = std::size_t{256} << 10;

// One header attribute: its name, type name and value's bytes.
struct Attribute {
  std::string name, type, value;
};

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

std::string bytes_of(const float* v, std::size_t n) { return std::string(reinterpret_cast<const char*>(v), n * sizeof(float)); }

// The time of writing as OpenImageIO writes it (its DateTime, OpenEXR's capDate).
std::string date_time() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local);
  return text;
}

std::string box(int x0, int y0, int x1, int y1) {
  std::string b;
  for (const int v : {x0, y0, x1, y1}) put(b, static_cast<int32_t>(v));
  return b;
}

// A channel of the part as the file stores it: its name, its bytes (2 half,
// 4 float) and where it lies in a packed pixel.
struct FileChannel {
  std::string name;
  std::size_t bytes = 4, offset = 0;
};

// The layout's channels in the file's order (by name).
std::vector<FileChannel> file_channels(const LayeredImage& layout) {
  std::vector<FileChannel> channels;
  const std::vector<const ImageLayer*> layers = every_layer(layout);
  const PackedLayout packed = packed_layout(layers);
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const std::size_t bytes = packed.layers[l].half ? 2 : 4;
    for (std::size_t c = 0; c < layers[l]->channels.size(); ++c)
      channels.push_back({layers[l]->channels[c], bytes, packed.layers[l].offset + c * bytes});
  }
  std::sort(channels.begin(), channels.end(), [](const FileChannel& a, const FileChannel& b) { return a.name < b.name; });
  return channels;
}

// The header: magic number, version, every attribute sorted by name, the end.
std::string header(const LayeredImage& layout, const ImageMetadata& metadata, const std::vector<FileChannel>& channels) {
  std::vector<Attribute> attributes;
  attributes.push_back({"Software", "string", "pathtracer " PT_VERSION});
  attributes.push_back({"capDate", "string", date_time()});
  std::string list;
  for (const FileChannel& c : channels) {
    list.append(c.name).push_back('\0');
    put(list, static_cast<int32_t>(c.bytes == 2 ? kHalf : kFloat));
    list.append(4, '\0');  // pLinear and three reserved bytes
    put(list, int32_t{1});  // x and y sampling
    put(list, int32_t{1});
  }
  list.push_back('\0');
  attributes.push_back({"channels", "chlist", list});
  attributes.push_back({"chromaticities", "chromaticities", bytes_of(kExrChromaticities.data(), kExrChromaticities.size())});
  attributes.push_back({"compression", "compression", std::string(1, '\0')});  // none
  attributes.push_back({"dataWindow", "box2i", box(layout.x, layout.y, layout.x + layout.width - 1, layout.y + layout.height - 1)});
  attributes.push_back({"displayWindow", "box2i", box(0, 0, layout.full_width - 1, layout.full_height - 1)});
  attributes.push_back({"lineOrder", "lineOrder", std::string(1, '\0')});  // increasing y
  const float one = 1.0f, center[2] = {0.0f, 0.0f};
  attributes.push_back({"pixelAspectRatio", "float", bytes_of(&one, 1)});
  attributes.push_back({"screenWindowCenter", "v2f", bytes_of(center, 2)});
  attributes.push_back({"screenWindowWidth", "float", bytes_of(&one, 1)});
  for (const auto& [name, value] : metadata.strings) attributes.push_back({name, "string", value});
  for (const auto& [name, value] : metadata.ints) {
    std::string v;
    put(v, static_cast<int32_t>(value));
    attributes.push_back({name, "int", v});
  }
  for (const auto& [name, value] : metadata.floats) attributes.push_back({name, "float", bytes_of(&value, 1)});
  for (const auto& [name, value] : metadata.matrices) attributes.push_back({name, "m44f", bytes_of(value.data(), value.size())});
  std::sort(attributes.begin(), attributes.end(), [](const Attribute& a, const Attribute& b) { return a.name < b.name; });

  bool long_names = std::any_of(channels.begin(), channels.end(), [](const FileChannel& c) { return c.name.size() >= kLongName; });
  std::string out;
  put(out, uint32_t{20000630});  // the magic number
  put(out, kVersion);
  for (const Attribute& a : attributes) {
    long_names = long_names || a.name.size() >= kLongName;
    out.append(a.name).push_back('\0');
    out.append(a.type).push_back('\0');
    put(out, static_cast<int32_t>(a.value.size()));
    out.append(a.value);
  }
  out.push_back('\0');
  if (long_names) {
    const uint32_t version = kVersion | kLongNamesFlag;
    std::memcpy(out.data() + 4, &version, sizeof version);
  }
  return out;
}

// Gathers one channel of `n` packed pixels (`step` bytes apart) into `out`.
template <std::size_t Bytes>
void gather(const unsigned char* in, std::size_t step, std::size_t n, unsigned char* out) {
  for (std::size_t x = 0; x < n; ++x) std::memcpy(out + x * Bytes, in + x * step, Bytes);
}

class UncompressedExrWriter final : public ExrBandWriter {
 public:
  UncompressedExrWriter(int fd, const LayeredImage& layout, std::vector<FileChannel> channels, std::size_t pixel_bytes)
      : fd_(fd), y_(layout.y), y_end_(layout.y + layout.height), width_(static_cast<std::size_t>(layout.width)),
        pixel_bytes_(pixel_bytes), channels_(std::move(channels)) {}
  ~UncompressedExrWriter() override {
    if (fd_ >= 0) ::close(fd_);
  }

  std::size_t row_bytes() const override { return pixel_bytes_ * width_; }

  bool write(int y0, int y1, const unsigned char* packed, std::string& error) override {
    if (!in_order(y0, y1, error)) return false;
    // Each row a chunk: its y, its size, then each channel's values of the row.
    const std::size_t chunk = 8 + row_bytes();
    buffer_.resize(static_cast<std::size_t>(y1 - y0) * chunk);
    tbb::parallel_for(tbb::blocked_range<int>(y0, y1, 8), [&](const tbb::blocked_range<int>& rows) {
      for (int y = rows.begin(); y < rows.end(); ++y) {
        unsigned char* out = buffer_.data() + static_cast<std::size_t>(y - y0) * chunk;
        const unsigned char* in = packed + static_cast<std::size_t>(y - y0) * row_bytes();
        const int32_t head[2] = {y, static_cast<int32_t>(row_bytes())};
        std::memcpy(out, head, sizeof head);
        out += sizeof head;
        for (const FileChannel& c : channels_) {
          (c.bytes == 2 ? gather<2> : gather<4>)(in + c.offset, pixel_bytes_, width_, out);
          out += c.bytes * width_;
        }
      }
    });
    if (!write_fd(fd_, buffer_.data(), buffer_.size(), error, kWritePiece)) return false;
    y_ = y1;
    return true;
  }

  bool write_lines(int y0, int y1, unsigned char* rows, std::string& error) override {
    if (!in_order(y0, y1, error)) return false;
    const std::size_t chunk = 8 + row_bytes();
    for (int y = y0; y < y1; ++y) {
      const int32_t head[2] = {y, static_cast<int32_t>(row_bytes())};
      std::memcpy(rows + static_cast<std::size_t>(y - y0) * chunk, head, sizeof head);
    }
    if (!write_fd(fd_, rows, static_cast<std::size_t>(y1 - y0) * chunk, error, kWritePiece)) return false;
    y_ = y1;
    return true;
  }

  bool close(std::string& error) override {
    if (fd_ < 0) return false;
    if (y_ != y_end_) {
      error = "the file was closed before its last row";
      return false;
    }
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) == 0) return true;
    error = std::strerror(errno);
    return false;
  }

 private:
  // Whether rows [y0, y1) follow the last written (`error` if not).
  bool in_order(int y0, int y1, std::string& error) const {
    if (fd_ >= 0 && y0 == y_ && y1 >= y0 && y1 <= y_end_) return true;
    error = "rows " + std::to_string(y0) + " to " + std::to_string(y1) + " written out of order";
    return false;
  }

  int fd_;
  int y_, y_end_;
  std::size_t width_, pixel_bytes_;
  std::vector<FileChannel> channels_;
  std::vector<unsigned char> buffer_;
};

// A name of the renderer's metadata, given no meaning of its own by the image module's writer.
bool plain_name(const std::string& name, bool matrix) {
  if (matrix) return name == "worldToCamera" || name == "worldToNDC";
  return (name.rfind("pathtracer:", 0) == 0 || name.rfind("cryptomatte/", 0) == 0) && name.size() <= kMaxNameLength &&
         name.find('\0') == std::string::npos;
}

}  // namespace

bool writes_uncompressed_exr(const LayeredImage& layout, const ImageMetadata& metadata, const ExrSettings& exr) {
  if (exr.compression != "none") return false;
  std::set<std::string> names;  // channels: each once
  for (const ImageLayer& layer : layout.layers)
    for (const std::string& c : layer.channels)
      if (c.empty() || c.size() > kMaxNameLength || c.find('\0') != std::string::npos || !names.insert(c).second)
        return false;
  names.clear();  // metadata: each once, whatever its case
  const auto once = [&](const std::string& name) {
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    return names.insert(lower).second;
  };
  for (const auto& [name, value] : metadata.strings)
    if (!plain_name(name, false) || !once(name) || value.find('\0') != std::string::npos) return false;
  for (const auto& [name, value] : metadata.ints)
    if (!plain_name(name, false) || !once(name)) return false;
  for (const auto& [name, value] : metadata.floats)
    if (!plain_name(name, false) || !once(name)) return false;
  for (const auto& [name, value] : metadata.matrices)
    if (!plain_name(name, true) || !once(name)) return false;
  return true;
}

LineLayout uncompressed_exr_lines(const LayeredImage& layout) {
  const std::vector<FileChannel> channels = file_channels(layout);
  const auto width = static_cast<std::size_t>(std::max(0, layout.width));
  // A channel's place in a packed pixel names it among the pixel's values
  // (both in the layers' order): the line of the channel at that place.
  std::vector<std::pair<std::size_t, LineChannel>> by_offset;
  std::size_t at = 8;  // the row's y and byte count
  for (const FileChannel& c : channels) {
    by_offset.push_back({c.offset, {at, c.bytes == 2}});
    at += c.bytes * width;
  }
  std::sort(by_offset.begin(), by_offset.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  LineLayout lines;
  for (const auto& [offset, line] : by_offset) lines.channels.push_back(line);
  lines.row_bytes = at;
  return lines;
}

std::unique_ptr<ExrBandWriter> open_uncompressed_exr(const std::string& path, const LayeredImage& layout,
                                                     const ImageMetadata& metadata, std::string& error) {
  if (layout.layers.empty() || layout.pixel_count() == 0) {
    error = "the image has no pixels";
    return nullptr;
  }
  std::vector<FileChannel> channels = file_channels(layout);
  const std::size_t pixel_bytes = packed_layout(layout).pixel_bytes;
  // The header, then the offset table: each row's chunk (its y, its size, its
  // values) at the offset that OpenEXR's writer gives it.
  std::string head = header(layout, metadata, channels);
  const std::size_t chunk = 8 + pixel_bytes * static_cast<std::size_t>(layout.width);
  uint64_t at = head.size() + 8 * static_cast<uint64_t>(layout.height);
  for (int y = 0; y < layout.height; ++y, at += chunk) put(head, at);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    error = std::strerror(errno);
    return nullptr;
  }
  auto writer = std::make_unique<UncompressedExrWriter>(fd, layout, std::move(channels), pixel_bytes);
  if (!write_fd(fd, head.data(), head.size(), error, kWritePiece)) return nullptr;
  return writer;
}

}  // namespace pt
