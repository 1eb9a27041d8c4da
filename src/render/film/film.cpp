#include "render/film/film.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <istream>
#include <ostream>

namespace pt {

namespace {

// State layout (version 1): the 8-byte magic, then uint32 version, width,
// height, then per pixel (row-major, row 0 at the top) r, g, b, weight as
// IEEE doubles and samples as uint64, all little-endian.
constexpr char kMagic[8] = {'P', 'T', 'F', 'I', 'L', 'M', '\r', '\n'};
constexpr uint32_t kStateVersion = 1;
static_assert(std::endian::native == std::endian::little, "film states are written in the host's byte order");

template <typename T>
void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
bool get(std::istream& in, T& v) {
  return static_cast<bool>(in.read(reinterpret_cast<char*>(&v), sizeof v));
}

}  // namespace

Film::Film(int width, int height)
    : width_(std::max(width, 0)), height_(std::max(height, 0)),
      pixels_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_)) {}

Image Film::image() const {
  Image out(width_, height_);
  for (std::size_t i = 0; i < pixels_.size(); ++i) out.pixels[i] = pixels_[i].value();
  return out;
}

void Film::clear() { std::fill(pixels_.begin(), pixels_.end(), PixelSum{}); }

bool Film::write_state(std::ostream& out) const {
  out.write(kMagic, sizeof kMagic);
  put(out, kStateVersion);
  put(out, static_cast<uint32_t>(width_));
  put(out, static_cast<uint32_t>(height_));
  for (const PixelSum& p : pixels_) {
    put(out, p.r);
    put(out, p.g);
    put(out, p.b);
    put(out, p.weight);
    put(out, p.samples);
  }
  return static_cast<bool>(out);
}

bool Film::read_state(std::istream& in, std::string& error) {
  char magic[sizeof kMagic];
  uint32_t version = 0, w = 0, h = 0;
  if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0) {
    error = "not a film state (bad magic)";
    return false;
  }
  if (!get(in, version) || version != kStateVersion) {
    error = "unsupported film state version " + std::to_string(version) + " (expected " +
            std::to_string(kStateVersion) + ")";
    return false;
  }
  if (!get(in, w) || !get(in, h)) {
    error = "truncated film state header";
    return false;
  }
  if (static_cast<int64_t>(w) != width_ || static_cast<int64_t>(h) != height_) {
    error = "film state is " + std::to_string(w) + "x" + std::to_string(h) + ", the render is " +
            std::to_string(width_) + "x" + std::to_string(height_);
    return false;
  }
  std::vector<PixelSum> pixels(pixels_.size());
  for (PixelSum& p : pixels) {
    if (!get(in, p.r) || !get(in, p.g) || !get(in, p.b) || !get(in, p.weight) || !get(in, p.samples)) {
      error = "truncated film state";
      return false;
    }
  }
  if (in.peek() != std::char_traits<char>::eof()) {
    error = "film state has trailing data";
    return false;
  }
  pixels_ = std::move(pixels);
  return true;
}

}  // namespace pt
