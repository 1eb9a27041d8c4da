// What a texture or environment map may cost once decoded. The size an image
// declares in its header is checked against these before anything is
// allocated, so a small file claiming 100000 x 100000 pixels is refused, not
// decoded (docs/scene-format.md, "Textures").
#pragma once

#include <cstdint>
#include <string>

namespace pt {

struct TextureLimits {
  int64_t max_pixels = int64_t{1} << 28;  // width * height, as the film (LoadOptions::max_pixels)
  // Decoded bytes: the channels read (at most 3) as float, plus the RGB texels.
  uint64_t max_bytes = uint64_t{1} << 32;

  // The bytes Texture::load allocates to decode `pixels` pixels of an image
  // with `file_channels` channels: the channels it reads (1 for grey and grey +
  // alpha, else 3) as float, and the RGB texels. Saturates at UINT64_MAX.
  static uint64_t decoded_bytes(uint64_t pixels, int file_channels);
  // Whether Texture::load decodes such an image (it refuses any other before
  // allocating anything); the memory pre-flight and the texture cache ask the same.
  bool admit(uint64_t pixels, int file_channels) const {
    return pixels <= static_cast<uint64_t>(max_pixels) && decoded_bytes(pixels, file_channels) <= max_bytes;
  }
  // The same for an image header (depth > 1: a volume, refused): false with
  // the message naming the declared size and the limits.
  bool check(int width, int height, int channels, int depth, std::string& error) const;
};

}  // namespace pt
