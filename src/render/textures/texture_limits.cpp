#include "render/textures/texture_limits.h"

#include "core/color.h"

namespace pt {

uint64_t TextureLimits::decoded_bytes(uint64_t pixels, int file_channels) {
  const uint64_t per_pixel = sizeof(float) * static_cast<uint64_t>(file_channels >= 3 ? 3 : 1) + sizeof(RGB);
  return pixels > UINT64_MAX / per_pixel ? UINT64_MAX : pixels * per_pixel;
}

bool TextureLimits::check(int w, int h, int nc, int depth, std::string& error) const {
  if (w <= 0 || h <= 0 || nc <= 0 || depth > 1) {
    error = "unsupported image layout (" + std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(nc) +
            " channels)";
    return false;
  }
  // Both factors are below 2^31: the product does not overflow 64 bits.
  const uint64_t count = static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
  if (admit(count, nc)) return true;
  const uint64_t bytes = decoded_bytes(count, nc);
  error = "the image declares " + std::to_string(w) + "x" + std::to_string(h) + " = " + std::to_string(count) +
          " pixels (" + std::to_string(bytes) + " bytes decoded); textures and environment maps may have at most " +
          std::to_string(max_pixels) + " pixels and " + std::to_string(max_bytes) + " bytes";
  return false;
}

}  // namespace pt
