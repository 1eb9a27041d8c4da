#include "io/image_io.h"

#include "io/atomic_file.h"


#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>

#include <OpenImageIO/imageio.h>

namespace pt {

namespace {

enum class FileKind { Exr, Png, Ppm, Unsupported };

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
  if (ext == ".ppm") return FileKind::Ppm;
  return FileKind::Unsupported;
}

float srgb_oetf(float v) { return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f; }

// The CGR course mapping: code = 255 * v^g with g = log(87/255) / log(1/4), the
// power curve through the course's one fixed point (a linear 0.25 background
// shows as 87/255 in its reference images), 0 -> 0 and 1 -> 255.
const float kCgrPower = static_cast<float>(std::log(87.0 / 255.0) / std::log(0.25));

// All 8-bit pixel codes of `image`, RGB interleaved, row 0 first.
std::vector<unsigned char> encode_8bit(const Image& image, const DisplaySettings& settings) {
  std::vector<unsigned char> bytes(image.pixels.size() * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const RGB& c = image.pixels[i];
    bytes[3 * i + 0] = display_encode(c.r, settings);
    bytes[3 * i + 1] = display_encode(c.g, settings);
    bytes[3 * i + 2] = display_encode(c.b, settings);
  }
  return bytes;
}

bool write_ppm(const std::string& path, const Image& image, const DisplaySettings& settings, std::string& error) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    error = std::strerror(errno);
    return false;
  }
  const std::vector<unsigned char> bytes = encode_8bit(image, settings);
  out << "P6\n" << image.width << ' ' << image.height << "\n255\n";
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    error = "write failed";
    return false;
  }
  return true;
}

// Writes through OpenImageIO with an explicit format name (the temporary file's
// name does not end in the real extension).
bool write_oiio(const std::string& path, const char* format, const Image& image, const DisplaySettings& settings,
                std::string& error) {
  auto out = OIIO::ImageOutput::create(format);
  if (!out) {
    error = OIIO::geterror();
    return false;
  }
  const bool is_float = std::strcmp(format, "openexr") == 0;
  OIIO::ImageSpec spec(image.width, image.height, 3, is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.attribute("Software", "pathtracer " PT_VERSION);
  if (is_float) {
    spec.attribute("compression", "zip");
    spec.attribute("oiio:ColorSpace", "Linear");
  } else if (settings.transform == DisplayTransform::Srgb) {
    spec.attribute("oiio:ColorSpace", "sRGB");
  }
  if (!out->open(path, spec)) {
    error = out->geterror();
    return false;
  }
  bool ok;
  if (is_float) {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  } else {
    const std::vector<unsigned char> bytes = encode_8bit(image, settings);
    ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  }
  if (!ok) error = out->geterror();
  if (!out->close() && ok) {
    error = out->geterror();
    ok = false;
  }
  return ok;
}

}  // namespace

unsigned char display_encode(float linear, const DisplaySettings& settings) {
  float v = linear * std::exp2(settings.exposure);
  if (!(v > 0.0f)) return 0;  // negative, zero and NaN
  v = std::min(v, 1.0f);
  switch (settings.transform) {
    case DisplayTransform::Srgb: v = srgb_oetf(v); break;
    case DisplayTransform::Linear: break;
    case DisplayTransform::CgrCourse: v = std::pow(v, kCgrPower); break;
  }
  return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

std::vector<std::string> supported_image_extensions() { return {".exr", ".png", ".ppm"}; }

bool is_supported_image_path(const std::string& path) { return file_kind(path) != FileKind::Unsupported; }

bool write_image(const std::string& path, const Image& image, const DisplaySettings& settings, std::string& error) {
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

  return write_atomically(
      path,
      [&](const std::string& tmp, std::string& why) {
        switch (kind) {
          case FileKind::Exr: return write_oiio(tmp, "openexr", image, settings, why);
          case FileKind::Png: return write_oiio(tmp, "png", image, settings, why);
          case FileKind::Ppm: return write_ppm(tmp, image, settings, why);
          case FileKind::Unsupported: break;
        }
        return false;
      },
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
