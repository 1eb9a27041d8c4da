#include "io/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>

#include "imagelib/image_library.h"
#include "io/atomic_file.h"
#include "io/exr_uncompressed.h"

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

// The image module, loaded on the first image written or read (nullptr and
// `error` if it cannot be).
const ImageLibrary* library(std::string& error) { return image_library(error); }

// The metadata of a PNG or JPEG, as text: PNG keeps every string attribute
// as a tEXt chunk but drops numbers, so numbers are written as text too
// ("pathtracer:partial" = "1"). OpenImageIO's JPEG writer keeps only the
// attributes it maps to EXIF/IPTC, so a JPEG gets them all as lines of its
// comment (ImageDescription, the JPEG COM marker), after the display line.
void add_display_metadata(DisplayImageFile& file, const ImageMetadata& metadata, const std::string& description) {
  file.text = metadata.strings;
  for (const auto& [name, value] : metadata.ints) file.text.emplace_back(name, std::to_string(value));
  for (const auto& [name, value] : metadata.floats) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(value));
    file.text.emplace_back(name, buf);
  }
  std::string comment = description;
  for (const auto& [name, value] : file.text) comment += "\n" + name + ": " + value;
  file.description = file.format == "jpeg" ? comment : description;
}

// A PNG or JPEG (`format`: "png", "jpeg"), encoded in memory by the image
// module and written with write_bytes: OpenImageIO's PNG writer does not check
// its writes (a full disk left a truncated file and reported success) and
// libjpeg ends the process on a failed write, so neither touches the disk.
// `alpha`: empty, or one straight alpha per pixel (PNG).
bool write_display_file(const std::string& path, const char* format, const Image& image,
                        const DisplaySettings& settings, const DisplayEncoder& display, const ImageMetadata& metadata,
                        std::string& error, const std::vector<float>& alpha = {}) {
  const ImageLibrary* lib = library(error);
  if (lib == nullptr) return false;
  DisplayImageFile file;
  file.format = format;
  file.width = image.width;
  file.height = image.height;
  file.channels = alpha.empty() ? 3 : 4;
  const std::vector<unsigned char> bytes = encode_8bit(image, display, alpha);
  file.pixels = bytes.data();
  file.srgb = settings.transform == DisplayTransform::Srgb && settings.ocio_config.empty();
  add_display_metadata(file, metadata, "display: " + display.description());
  std::vector<unsigned char> encoded;
  return lib->encode(file, encoded, error) && write_bytes(path, encoded.data(), encoded.size(), error);
}

// An RGB image as the one float layer of an EXR (R, G, B).
bool write_exr_rgb(const std::string& path, const Image& image, const ImageMetadata& metadata, std::string& error) {
  const ImageLibrary* lib = library(error);
  if (lib == nullptr) return false;
  LayeredImage layered;
  layered.full_width = layered.width = image.width;
  layered.full_height = layered.height = image.height;
  ImageLayer rgb;
  rgb.channels = {"R", "G", "B"};
  rgb.values.reserve(image.pixels.size() * 3);
  for (const RGB& p : image.pixels) rgb.values.insert(rgb.values.end(), {p.r, p.g, p.b});
  layered.layers.push_back(std::move(rgb));
  return lib->write_exr(path, layered, metadata, ExrSettings{}, error);
}

}  // namespace

std::vector<std::string> supported_image_extensions() { return {".exr", ".png", ".jpg", ".jpeg", ".ppm"}; }

bool is_supported_image_path(const std::string& path) { return file_kind(path) != FileKind::Unsupported; }

bool is_exr_path(const std::string& path) { return file_kind(path) == FileKind::Exr; }

bool needs_image_library(const std::string& path) {
  const FileKind kind = file_kind(path);
  return kind == FileKind::Exr || kind == FileKind::Png || kind == FileKind::Jpeg;
}

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
          case FileKind::Exr: return write_exr_rgb(tmp, image, metadata, why);
          case FileKind::Png: return write_display_file(tmp, "png", image, settings, *display, metadata, why, alpha);
          case FileKind::Jpeg: return write_display_file(tmp, "jpeg", image, settings, *display, metadata, why);
          case FileKind::Ppm: return write_ppm(tmp, image, *display, why);
          case FileKind::Unsupported: break;
        }
        return false;
      },
      error);
}

// An EXR of `image`'s size, written by `write` into a temporary file that
// replaces `path` only once it is complete.
bool write_exr_atomically(const std::string& path, const LayeredImage& image, std::string& error,
                          const std::function<bool(const std::string&, std::string&)>& write) {
  if (image.width <= 0 || image.height <= 0) {
    error = "cannot write '" + path + "': the image is empty";
    return false;
  }
  return write_atomically(path, write, error);
}

// The same, written through the image module.
bool write_exr_file(const std::string& path, const LayeredImage& image, std::string& error,
                    const std::function<bool(const ImageLibrary&, const std::string&, std::string&)>& write) {
  return write_exr_atomically(path, image, error, [&](const std::string& tmp, std::string& why) {
    const ImageLibrary* lib = library(why);
    return lib != nullptr && write(*lib, tmp, why);
  });
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
  return write_exr_file(path, image, error, [&](const ImageLibrary& lib, const std::string& tmp, std::string& why) {
    return lib.write_exr(tmp, image, metadata, exr, why);
  });
}

bool write_exr_bands(const std::string& path, const LayeredImage& layout, const ImageMetadata& metadata,
                     const ExrSettings& exr, const std::function<bool(ExrBandWriter&, std::string&)>& write,
                     std::string& error) {
  const auto finish = [&](const std::unique_ptr<ExrBandWriter>& writer, std::string& why) {
    return writer != nullptr && write(*writer, why) && writer->close(why);
  };
  if (writes_uncompressed_exr(layout, metadata, exr))  // the same bytes, without loading the image module
    return write_exr_atomically(path, layout, error, [&](const std::string& tmp, std::string& why) {
      return finish(open_uncompressed_exr(tmp, layout, metadata, why), why);
    });
  return write_exr_file(path, layout, error, [&](const ImageLibrary& lib, const std::string& tmp, std::string& why) {
    return finish(lib.open_exr(tmp, layout, metadata, exr, why), why);
  });
}

bool read_image(const std::string& path, Image& out, std::string& error) {
  std::string why;
  const ImageLibrary* lib = library(why);
  const std::unique_ptr<ImageReader> in = lib != nullptr ? lib->open(path, false, why) : nullptr;
  if (!in) {
    error = "cannot read '" + path + "': " + why;
    return false;
  }
  const ImageHeader& h = in->header();
  const int w = h.width, ht = h.height, nc = h.nchannels;
  if (w <= 0 || ht <= 0 || nc <= 0 || h.depth > 1) {
    error = "cannot read '" + path + "': unsupported image layout";
    return false;
  }
  std::vector<float> data(static_cast<std::size_t>(w) * static_cast<std::size_t>(ht) * static_cast<std::size_t>(nc));
  if (!in->read(nc, data.data(), why)) {
    error = "cannot read '" + path + "': " + why;
    return false;
  }
  out = Image(w, ht);
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    const float* p = &data[i * static_cast<std::size_t>(nc)];
    out.pixels[i] = nc >= 3 ? RGB(p[0], p[1], p[2]) : RGB(p[0]);
  }
  return true;
}

}  // namespace pt
