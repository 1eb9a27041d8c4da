#include "render/textures/texture.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <utility>

#include "core/file_access.h"
#include "core/srgb.h"
#include "imagelib/image_library.h"

namespace pt {

namespace {

// Expands nc channels (grey, grey+alpha, RGB, RGBA, ...) to RGB. Alpha is ignored.
RGB to_rgb(const float* p, int nc) {
  if (nc >= 3) return {p[0], p[1], p[2]};
  return RGB(p[0]);
}

int wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

RGB bilinear(const RasterImage& img, Vec2f uv) {
  if (img.width <= 0 || img.height <= 0) return RGB(1.0f);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return img.pixels[0];
  // Texel centres sit at half-integer positions: uv (0,0) is the top-left
  // corner of the top-left texel.
  const float x = uv.x * static_cast<float>(img.width) - 0.5f;
  const float y = uv.y * static_cast<float>(img.height) - 0.5f;
  const float fx0 = std::floor(x), fy0 = std::floor(y);
  const float tx = x - fx0, ty = y - fy0;
  // Reduce before converting to int so huge uv values cannot overflow.
  const int x0 = wrap(static_cast<int>(std::fmod(fx0, static_cast<float>(img.width))), img.width);
  const int y0 = wrap(static_cast<int>(std::fmod(fy0, static_cast<float>(img.height))), img.height);
  const int x1 = wrap(x0 + 1, img.width), y1 = wrap(y0 + 1, img.height);
  auto at = [&](int ix, int iy) { return img.pixels[static_cast<std::size_t>(iy) * img.width + ix]; };
  const RGB top = at(x0, y0) * (1.0f - tx) + at(x1, y0) * tx;
  const RGB bottom = at(x0, y1) * (1.0f - tx) + at(x1, y1) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

float mean(RGB c) { return (c.r + c.g + c.b) * (1.0f / 3.0f); }

// The colour of a cached image: its first three channels, or its grey one.
RGB cached_rgb(const CachedImage& img, Vec3f c, Vec3f dcdx, Vec3f dcdy) {
  float v[3];
  const int n = img.channels >= 3 ? 3 : 1;
  img.cache->lookup(img, {c.x, c.y}, {dcdx.x, dcdx.y}, {dcdy.x, dcdy.y}, 0, n, v);
  return n == 3 ? RGB(v[0], v[1], v[2]) : RGB(v[0]);
}

}  // namespace

Vec3f TextureMapping::coordinates(const TexCoord& tc, Vec3f& dcdx, Vec3f& dcdy) const {
  Vec3f c = object ? tc.p : Vec3f(tc.uv.x, tc.uv.y, 0.0f);
  dcdx = object ? tc.dpdx : Vec3f(tc.duvdx.x, tc.duvdx.y, 0.0f);
  dcdy = object ? tc.dpdy : Vec3f(tc.duvdy.x, tc.duvdy.y, 0.0f);
  if (transform) {
    c = transform->inverse_point(c);
    dcdx = transform->inverse_vector(dcdx);
    dcdy = transform->inverse_vector(dcdy);
  }
  dcdx = dcdx * scale;
  dcdy = dcdy * scale;
  return c * scale;
}

Texture::Texture(int width, int height, std::vector<RGB> pixels)
    : source_(RasterImage{width, height, std::move(pixels)}) {}

Texture::Texture(Source source, TextureMapping mapping) : source_(std::move(source)), mapping_(std::move(mapping)) {}

int Texture::width() const {
  const RasterImage* r = std::get_if<RasterImage>(&source_);
  return r != nullptr ? r->width : 0;
}

int Texture::height() const {
  const RasterImage* r = std::get_if<RasterImage>(&source_);
  return r != nullptr ? r->height : 0;
}

RGB Texture::eval(const TexCoord& tc) const {
  Vec3f dcdx, dcdy;
  const Vec3f c = mapping_.coordinates(tc, dcdx, dcdy);
  struct Visit {
    Vec3f c, dx, dy;
    RGB operator()(const RasterImage& r) const { return bilinear(r, {c.x, c.y}); }
    RGB operator()(const CachedImage& img) const { return cached_rgb(img, c, dx, dy); }
    RGB operator()(const CheckerTexture& t) const { return evaluate(t, c, dx, dy); }
    RGB operator()(const NoiseTexture& t) const { return evaluate(t, c, dx, dy); }
  };
  return std::visit(Visit{c, dcdx, dcdy}, source_);
}

float Texture::alpha(const TexCoord& tc) const {
  if (const CachedImage* img = std::get_if<CachedImage>(&source_); img != nullptr && img->alpha_channel >= 0) {
    Vec3f dcdx, dcdy;
    const Vec3f c = mapping_.coordinates(tc.point(), dcdx, dcdy);
    float a = 1.0f;
    img->cache->lookup(*img, {c.x, c.y}, {}, {}, img->alpha_channel, 1, &a);
    return a;
  }
  return mean(eval(tc.point()));
}

namespace {

// Decodes the image `in` opened into linear RGB texels (see Texture::load).
bool decode(ImageReader& in, Texture& out, std::string& error, const TextureLimits& limits, bool raw) {
  const ImageHeader& spec = in.header();
  if (!limits.check(spec.width, spec.height, spec.nchannels, spec.depth, error)) return false;
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  // Grey (and grey + alpha) images need one channel, the rest three.
  const int channels = nc >= 3 ? 3 : 1;
  const std::size_t count = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<float> data(count * static_cast<std::size_t>(channels));
  if (!in.read(channels, data.data(), error)) return false;
  const bool srgb = !raw && spec.srgb_encoded;

  std::vector<RGB> pixels(count);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    RGB c = to_rgb(&data[i * static_cast<std::size_t>(channels)], channels);
    if (srgb) c = {srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b)};
    pixels[i] = c;
  }
  out = Texture(w, h, std::move(pixels));
  return true;
}

}  // namespace

bool Texture::load(const std::string& path, Texture& out, std::string& error, const TextureLimits& limits,
                   bool raw) {
  if (const std::string why = why_unreadable(path); !why.empty()) {
    error = "cannot open the file: " + why;
    return false;
  }
  const ImageLibrary* lib = image_library(error);
  if (lib == nullptr) return false;
  // Colour as stored, not premultiplied by alpha.
  const std::unique_ptr<ImageReader> in = lib->open(path, /*unassociated_alpha=*/true, error);
  return in != nullptr && decode(*in, out, error, limits, raw);
}

}  // namespace pt
