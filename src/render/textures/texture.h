// Textures: what materials hold (docs/textures.md). A texture is one source,
//  - an image in memory, decoded once with OpenImageIO into linear float RGB
//    and looked up bilinearly with repeat wrapping (environment maps and the
//    background image, whose whole image is needed, and textures built in code);
//  - an image in the texture cache (texture_cache.h): MIP-mapped, tiled,
//    filtered over the lookup's footprint (every image texture of a scene);
//  - a procedural checker or noise (procedural.h),
// read through a mapping: the hit's uv or its object-space position, scaled
// and moved by the texture's own transform. uv (0,0) is the image's top-left
// pixel corner, u to the right, v downwards.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/color.h"
#include "core/math.h"
#include "core/transform.h"
#include "render/textures/procedural.h"
#include "render/textures/tex_coord.h"
#include "render/textures/texture_cache.h"
#include "render/textures/texture_limits.h"

namespace pt {

// Where a texture reads: texture-space coordinates c = scale * T^-1(x), with
// x = (u, v, 0) or the object-space position, T the texture's transform (it
// moves the pattern as a shape's transform moves the shape) and `scale` the
// pattern's frequency. The footprint goes through the same linear map.
struct TextureMapping {
  bool object = false;  // object-space position, else uv
  Vec3f scale{1.0f, 1.0f, 1.0f};
  std::optional<Transform> transform;

  Vec3f coordinates(const TexCoord& tc, Vec3f& dcdx, Vec3f& dcdy) const;
};

// An image decoded into memory.
struct RasterImage {
  int width = 0, height = 0;
  std::vector<RGB> pixels;  // row-major, row 0 at the top
};

class Texture {
 public:
  using Source = std::variant<RasterImage, CachedImage, CheckerTexture, NoiseTexture>;

  Texture() = default;  // an empty image: white everywhere
  Texture(int width, int height, std::vector<RGB> pixels);
  explicit Texture(Source source, TextureMapping mapping = {});

  // Decodes an image file into memory; 8-bit sRGB-encoded images are
  // linearised unless `raw` (values used as they are). Returns false and fills
  // `error` if the file cannot be read or declares a size beyond `limits`.
  static bool load(const std::string& path, Texture& out, std::string& error, const TextureLimits& limits = {},
                   bool raw = false);

  // The colour over the footprint of `tc` (a point lookup where it has none).
  RGB eval(const TexCoord& tc) const;
  // A point lookup at `uv` (an in-memory image: bilinear, repeat wrap).
  RGB lookup(Vec2f uv) const { return eval(TexCoord(uv)); }
  // Coverage at a point, for alpha cutouts: an image's alpha channel where it
  // has one, else the mean of the colour's channels (a grey mask; for a
  // procedural texture, its colours' means).
  float alpha(const TexCoord& tc) const;

  // In-memory images: texel (x, y), 0 <= x < width, 0 <= y < height, row 0 at the top.
  const RGB& texel(int x, int y) const {
    const RasterImage& r = std::get<RasterImage>(source_);
    return r.pixels[static_cast<std::size_t>(y) * r.width + x];
  }
  int width() const;
  int height() const;
  const Source& source() const { return source_; }
  const TextureMapping& mapping() const { return mapping_; }

 private:
  Source source_;
  TextureMapping mapping_;
};

}  // namespace pt
