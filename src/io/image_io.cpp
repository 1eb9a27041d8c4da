#include "io/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "io/atomic_file.h"
#include "io/exr_layers.h"

namespace pt {

namespace {

enum class FileKind { Exr, Png, Jpeg, Ppm, Unsupported };

std::string lower_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

FileKind file_kind(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".exr") return FileKind::Exr;
  if (ext == ".png") return FileKind::Png;
  if (ext == ".jpg" || ext == ".jpeg") return FileKind::Jpeg;
  if (ext == ".ppm") return FileKind::Ppm;
  return FileKind::Unsupported;
}

// All 8-bit pixel codes of `image`, RGB interleaved, row 0 first; RGBA when
// `alpha` (one value per pixel, clamped to [0, 1]) is not empty.
std::vector<unsigned char> encode_8bit(const Image& image, const DisplayEncoder& display,
                                       const std::vector<float>& alpha = {}) {
  std::vector<unsigned char> bytes(image.pixels.size() * 3);
  display.encode(image.pixels.data(), image.pixels.size(), bytes.data());
  if (alpha.empty()) return bytes;
  std::vector<unsigned char> rgba(image.pixels.size() * 4);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    std::copy_n(&bytes[i * 3], 3, &rgba[i * 4]);
    rgba[i * 4 + 3] = static_cast<unsigned char>(std::lround(std::clamp(alpha[i], 0.0f, 1.0f) * 255.0f));
  }
  return rgba;
}

// The beauty of the data window as a (premultiplied) RGB image, and its alpha
// when asked for.
Image beauty_rgb(const LayeredImage& image, std::vector<float>* alpha) {
  const ImageLayer& beauty = image.layers[0];
  const std::size_t n = beauty.channels.size();
  Image rgb(image.width, image.height);
  for (std::size_t i = 0; i < rgb.pixels.size() && (i + 1) * n <= beauty.values.size(); ++i) {
    rgb.pixels[i] = RGB(beauty.values[i * n], beauty.values[i * n + 1], beauty.values[i * n + 2]);
    if (alpha != nullptr) alpha->push_back(n >= 4 ? beauty.values[i * n + 3] : 1.0f);
  }
  return rgb;
}

// PNG's alpha is straight: the colour of a partly covered pixel is its
// premultiplied value divided by its alpha (black where alpha is 0).
void unpremultiply(Image& image, const std::vector<float>& alpha) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const float a = std::clamp(alpha[i], 0.0f, 1.0f);
    image.pixels[i] = a > 0.0f ? image.pixels[i] * (1.0f / a) : RGB();
  }
}

bool write_ppm(const std::string& path, const Image& image, const DisplayEncoder& display, std::string& error) {
  const std::vector<unsigned char> bytes = encode_8bit(image, display);
  std::string file = "P6\n" + std::to_string(image.width) + ' ' + std::to_string(image.height) + "\n255\n";
  file.append(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return write_bytes(path, file.data(), file.size(), error);
}

// The metadata of a PNG or JPEG, as text: PNG keeps every string attribute
// as a tEXt chunk but drops numbers, so numbers are written as text too
// ("pathtracer:partial" = "1"). OpenImageIO's JPEG writer keeps only the
// attributes it maps to EXIF/IPTC, so a JPEG gets them all as lines of its
// comment (ImageDescription, the JPEG COM marker), after the display line.
void add_display_metadata(OIIO::ImageSpec& spec, const ImageMetadata& metadata, bool jpeg,
                          const std::string& description) {
  std::vector<std::pair<std::string, std::string>> text = metadata.strings;
  for (const auto& [name, value] : metadata.ints) text.emplace_back(name, std::to_string(value));
  for (const auto& [name, value] : metadata.floats) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(value));
    text.emplace_back(name, buf);
  }
  std::string comment = description;
  for (const auto& [name, value] : text) {
    spec.attribute(name, value);
    comment += "\n" + name + ": " + value;
  }
  spec.attribute("ImageDescription", jpeg ? comment : description);
}

// Writes through OpenImageIO with an explicit format name (the temporary file's
// name does not end in the real extension). The file is encoded in memory and
// then written with write_bytes: OpenImageIO's PNG writer does not check its
// writes (a full disk left a truncated file and reported success) and libjpeg
// ends the process on a failed write, so neither touches the disk itself.
// `alpha` (8-bit formats only): empty, or one straight alpha per pixel.
bool write_oiio(const std::string& path, const char* format, const Image& image, const DisplaySettings& settings,
                const DisplayEncoder* display, const ImageMetadata& metadata, std::string& error,
                const std::vector<float>& alpha = {}) {
  auto out = OIIO::ImageOutput::create(format);
  if (!out) {
    error = OIIO::geterror();
    return false;
  }
  const bool is_float = std::strcmp(format, "openexr") == 0;
  const int channels = alpha.empty() || is_float ? 3 : 4;
  OIIO::ImageSpec spec(image.width, image.height, channels, is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (channels == 4) spec.alpha_channel = 3;
  spec.attribute("Software", "pathtracer " PT_VERSION);
  if (is_float) {
    spec.attribute("compression", "zip");
    spec.attribute("oiio:ColorSpace", "Linear");
    add_image_metadata(spec, metadata, true);
  } else {
    if (settings.transform == DisplayTransform::Srgb && settings.ocio_config.empty()) spec.attribute("oiio:ColorSpace", "sRGB");
    const bool jpeg = std::strcmp(format, "jpeg") == 0;
    if (jpeg) spec.attribute("Compression", "jpeg:95");
    add_display_metadata(spec, metadata, jpeg, "display: " + display->description());
  }
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  OIIO::Filesystem::IOProxy* proxy = &memory;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out->open(path, spec)) {
    error = out->geterror();
    return false;
  }
  bool ok;
  if (is_float) {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  } else {
    const std::vector<unsigned char> bytes = encode_8bit(image, *display, channels == 4 ? alpha : std::vector<float>{});
    ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  }
  if (!ok) error = out->geterror();
  if (!out->close() && ok) {
    error = out->geterror();
    ok = false;
  }
  return ok && write_bytes(path, encoded.data(), encoded.size(), error);
}

}  // namespace

std::vector<std::string> supported_image_extensions() { return {".exr", ".png", ".jpg", ".jpeg", ".ppm"}; }

bool is_supported_image_path(const std::string& path) { return file_kind(path) != FileKind::Unsupported; }

bool is_exr_path(const std::string& path) { return file_kind(path) == FileKind::Exr; }

std::vector<std::string> exr_compression_names() {
  return {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"};
}

bool check_exr_compression(const std::string& compression, std::string& error) {
  const std::size_t colon = compression.find(':');
  const std::string name = compression.substr(0, colon);
  const std::vector<std::string> names = exr_compression_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    error = "unknown EXR compression '" + compression + "'; valid names are:";
    for (const std::string& n : names) error += " " + n;
    error += " (dwaa and dwab take a level: dwaa:45)";
    return false;
  }
  if (colon == std::string::npos) return true;
  const std::string level = compression.substr(colon + 1);
  char* end = nullptr;
  const double value = std::strtod(level.c_str(), &end);
  if ((name != "dwaa" && name != "dwab") || level.empty() || *end != '\0' || !(value > 0.0) ||
      !std::isfinite(value)) {
    error = "EXR compression '" + compression + "': only dwaa and dwab take a level, a number > 0 (dwaa:45)";
    return false;
  }
  return true;
}

bool exr_compression_rounds_floats(const std::string& compression) { return compression.rfind("pxr24", 0) == 0; }

namespace {

bool write_image_with_alpha(const std::string& path, const Image& image, const std::vector<float>& alpha,
                            const DisplaySettings& settings, std::string& error, const ImageMetadata& metadata) {
  const FileKind kind = file_kind(path);
  if (kind == FileKind::Unsupported) {
    error = "cannot write '" + path + "': unsupported image extension '" + lower_extension(path) +
            "' (supported:";
    for (const std::string& e : supported_image_extensions()) error += " " + e;
    error += ")";
    return false;
  }
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
    error = "cannot write '" + path + "': the image is empty or inconsistent";
    return false;
  }
  // Display images: the colour pipeline is built (and its names checked) first.
  std::unique_ptr<DisplayEncoder> display;
  if (kind != FileKind::Exr) {
    std::string why;
    display = DisplayEncoder::create(settings, why);
    if (!display) {
      error = "cannot write '" + path + "': " + why;
      return false;
    }
  }
  return write_atomically(
      path,
      [&](const std::string& tmp, std::string& why) {
        switch (kind) {
          case FileKind::Exr: return write_oiio(tmp, "openexr", image, settings, nullptr, metadata, why);
          case FileKind::Png: return write_oiio(tmp, "png", image, settings, display.get(), metadata, why, alpha);
          case FileKind::Jpeg: return write_oiio(tmp, "jpeg", image, settings, display.get(), metadata, why);
          case FileKind::Ppm: return write_ppm(tmp, image, *display, why);
          case FileKind::Unsupported: break;
        }
        return false;
      },
      error);
}

}  // namespace

bool write_image(const std::string& path, const Image& image, const DisplaySettings& settings, std::string& error,
                 const ImageMetadata& metadata) {
  return write_image_with_alpha(path, image, {}, settings, error, metadata);
}

bool write_layered_image(const std::string& path, const LayeredImage& image, const DisplaySettings& settings,
                         std::string& error, const ImageMetadata& metadata, const ExrSettings& exr) {
  if (file_kind(path) != FileKind::Exr) {
    if (image.layers.empty() || image.layers[0].channels.size() < 3) {
      error = "cannot write '" + path + "': the image has no beauty layer";
      return false;
    }
    std::vector<float> alpha;
    const bool with_alpha = settings.alpha && file_kind(path) == FileKind::Png;
    Image rgb = beauty_rgb(image, with_alpha ? &alpha : nullptr);
    if (with_alpha) unpremultiply(rgb, alpha);
    return write_image_with_alpha(path, rgb, alpha, settings, error, metadata);
  }
  if (image.width <= 0 || image.height <= 0) {
    error = "cannot write '" + path + "': the image is empty";
    return false;
  }
  return write_atomically(
      path, [&](const std::string& tmp, std::string& why) { return write_exr_layers(tmp, image, metadata, exr, why); },
      error);
}

bool read_image(const std::string& path, Image& out, std::string& error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    error = "cannot read '" + path + "': " + OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w <= 0 || h <= 0 || nc <= 0 || spec.depth > 1) {
    error = "cannot read '" + path + "': unsupported image layout";
    return false;
  }
  std::vector<float> data(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(nc));
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, data.data())) {
    error = "cannot read '" + path + "': " + in->geterror();
    return false;
  }
  out = Image(w, h);
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    const float* p = &data[i * static_cast<std::size_t>(nc)];
    out.pixels[i] = nc >= 3 ? RGB(p[0], p[1], p[2]) : RGB(p[0]);
  }
  return true;
}

}  // namespace pt
