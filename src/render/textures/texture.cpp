#include "render/textures/texture.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/file_access.h"

namespace pt {

namespace {

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

// Integer images (8- and 16-bit PNG, JPEG, ...) are sRGB-encoded unless the
// file says it is linear; float images (EXR, HDR) are linear as they are.
bool is_srgb_encoded(const OIIO::ImageSpec& spec) {
  if (spec.format.is_floating_point()) return false;
  const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
  return !(cs == "Linear" || cs == "linear" || cs == "lin_srgb" || cs == "scene_linear");
}

// Expands nc channels (grey, grey+alpha, RGB, RGBA, ...) to RGB. Alpha is ignored:
// a texture here only modulates the diffuse colour.
RGB to_rgb(const float* p, int nc) {
  if (nc >= 3) return {p[0], p[1], p[2]};
  return RGB(p[0]);
}

int wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

}  // namespace

uint64_t TextureLimits::decoded_bytes(uint64_t pixels, int file_channels) {
  const uint64_t per_pixel = sizeof(float) * static_cast<uint64_t>(file_channels >= 3 ? 3 : 1) + sizeof(RGB);
  return pixels > UINT64_MAX / per_pixel ? UINT64_MAX : pixels * per_pixel;
}

Texture::Texture(int width, int height, std::vector<RGB> pixels)
    : width_(width), height_(height), pixels_(std::move(pixels)) {}

namespace {

// Decodes the image `in` opened into linear RGB texels (see Texture::load).
bool decode(OIIO::ImageInput& in, Texture& out, std::string& error, const TextureLimits& limits, bool raw) {
  const OIIO::ImageSpec& spec = in.spec();
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w <= 0 || h <= 0 || nc <= 0 || spec.depth > 1) {
    error = "unsupported image layout (" + std::to_string(w) + "x" + std::to_string(h) + ", " +
            std::to_string(nc) + " channels)";
    return false;
  }
  // Grey (and grey + alpha) images need one channel, the rest three.
  const int channels = nc >= 3 ? 3 : 1;
  // Both factors are below 2^31: the product does not overflow 64 bits.
  const uint64_t count = static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
  if (!limits.admit(count, nc)) {
    const uint64_t bytes = TextureLimits::decoded_bytes(count, nc);
    error = "the image declares " + std::to_string(w) + "x" + std::to_string(h) + " = " + std::to_string(count) +
            " pixels (" + std::to_string(bytes) + " bytes decoded); textures and environment maps may have at most " +
            std::to_string(limits.max_pixels) + " pixels and " + std::to_string(limits.max_bytes) + " bytes";
    return false;
  }
  std::vector<float> data(static_cast<std::size_t>(count) * static_cast<std::size_t>(channels));
  if (!in.read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data())) {
    error = in.geterror();
    if (error.empty()) error = "cannot decode image";
    return false;
  }
  const bool srgb = !raw && is_srgb_encoded(spec);

  std::vector<RGB> pixels(static_cast<std::size_t>(count));
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
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // do not premultiply colour by alpha
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) {
    error = OIIO::geterror();
    if (error.empty()) error = "cannot open image";
    return false;
  }
  return decode(*in, out, error, limits, raw);
}

bool Texture::load_memory(const std::vector<unsigned char>& bytes, const std::string& format, Texture& out,
                          std::string& error, const TextureLimits& limits, bool raw) {
  // OpenImageIO reads from memory through an IOProxy, for the formats that
  // support one (PNG, JPEG, ...); the name only chooses the reader.
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  const std::string name = "embedded." + (format.empty() ? std::string("png") : format);
  auto in = OIIO::ImageInput::create(name, false, nullptr, &memory);
  OIIO::ImageSpec config, spec;
  config.attribute("oiio:UnassociatedAlpha", 1);
  if (!in || !in->supports("ioproxy") || !in->set_ioproxy(&memory) || !in->open(name, spec, config)) {
    error = in ? in->geterror() : OIIO::geterror();
    if (error.empty()) error = "cannot decode the embedded '" + format + "' image";
    return false;
  }
  return decode(*in, out, error, limits, raw);
}

RGB Texture::lookup(Vec2f uv) const {
  if (width_ <= 0 || height_ <= 0) return RGB(1.0f);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return pixels_[0];
  // Texel centres sit at half-integer positions: uv (0,0) is the top-left
  // corner of the top-left texel.
  const float x = uv.x * static_cast<float>(width_) - 0.5f;
  const float y = uv.y * static_cast<float>(height_) - 0.5f;
  const float fx0 = std::floor(x), fy0 = std::floor(y);
  const float tx = x - fx0, ty = y - fy0;
  // Reduce before converting to int so huge uv values cannot overflow.
  const int x0 = wrap(static_cast<int>(std::fmod(fx0, static_cast<float>(width_))), width_);
  const int y0 = wrap(static_cast<int>(std::fmod(fy0, static_cast<float>(height_))), height_);
  const int x1 = wrap(x0 + 1, width_), y1 = wrap(y0 + 1, height_);
  auto at = [&](int ix, int iy) { return pixels_[static_cast<std::size_t>(iy) * width_ + ix]; };
  const RGB top = at(x0, y0) * (1.0f - tx) + at(x1, y0) * tx;
  const RGB bottom = at(x0, y1) * (1.0f - tx) + at(x1, y1) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

}  // namespace pt
