// The pt_oiio module: the image library (imagelib/image_library.h) through
// OpenImageIO. Built as a MODULE library, opened with dlopen on first use;
// its only exported symbols are the two C entry points at the bottom.
#include <cstring>
#include <memory>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "imagelib/image_library.h"
#include "imagelib/oiio/exr_writer.h"
#include "imagelib/oiio/srgb_input.h"
#include "imagelib/oiio/texture_system.h"

namespace pt {
namespace {

ImageHeader header_of(const OIIO::ImageSpec& spec) {
  ImageHeader h;
  h.width = spec.width;
  h.height = spec.height;
  h.depth = spec.depth;
  h.nchannels = spec.nchannels;
  h.alpha_channel = spec.alpha_channel;
  h.srgb_encoded = srgb_encoded(spec);
  return h;
}

std::string or_default(std::string error, const char* fallback) { return error.empty() ? fallback : error; }

class OiioReader final : public ImageReader {
 public:
  OiioReader(std::unique_ptr<OIIO::ImageInput> in, std::unique_ptr<OIIO::Filesystem::IOMemReader> memory = {})
      : memory_(std::move(memory)), in_(std::move(in)), header_(header_of(in_->spec())) {}
  const ImageHeader& header() const override { return header_; }
  bool read(int channels, float* out, std::string& error) override {
    if (in_->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, out)) return true;
    error = or_default(in_->geterror(), "cannot decode image");
    return false;
  }

 private:
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory_;  // outlives in_
  std::unique_ptr<OIIO::ImageInput> in_;
  ImageHeader header_;
};

// Encodes through OpenImageIO into memory (the caller writes the bytes:
// OpenImageIO's PNG writer does not check its writes, and libjpeg ends the
// process on a failed write, so neither touches the disk itself).
bool encode_display(const DisplayImageFile& image, std::vector<unsigned char>& encoded, std::string& error) {
  auto out = OIIO::ImageOutput::create(image.format);
  if (!out) {
    error = or_default(OIIO::geterror(), "no image writer");
    return false;
  }
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::UINT8);
  if (image.channels == 4) spec.alpha_channel = 3;
  spec.attribute("Software", "pathtracer " PT_VERSION);
  if (image.srgb) spec.attribute("oiio:ColorSpace", "sRGB");
  if (image.format == "jpeg") spec.attribute("Compression", "jpeg:95");
  for (const auto& [name, value] : image.text) spec.attribute(name, value);
  spec.attribute("ImageDescription", image.description);
  OIIO::Filesystem::IOVecOutput memory(encoded);
  OIIO::Filesystem::IOProxy* proxy = &memory;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out->open("memory." + image.format, spec)) {
    error = out->geterror();
    return false;
  }
  bool ok = out->write_image(OIIO::TypeDesc::UINT8, image.pixels);
  if (!ok) error = out->geterror();
  if (!out->close() && ok) {
    error = out->geterror();
    ok = false;
  }
  return ok;
}

class OiioLibrary final : public ImageLibrary {
 public:
  std::string version() const override {
    const int v = OIIO::openimageio_version();
    return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
  }

  std::unique_ptr<ImageReader> open(const std::string& path, bool unassociated_alpha,
                                    std::string& error) const override {
    OIIO::ImageSpec config;
    if (unassociated_alpha) config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) {
      error = or_default(OIIO::geterror(), "cannot open image");
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(in));
  }

  // OpenImageIO reads from memory through an IOProxy, for the formats that
  // support one (PNG, JPEG, ...); the name only chooses the reader.
  std::unique_ptr<ImageReader> open_memory(const unsigned char* bytes, std::size_t size, const std::string& format,
                                           std::string& error) const override {
    auto memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes, size);
    const std::string name = "embedded." + (format.empty() ? std::string("png") : format);
    auto in = OIIO::ImageInput::create(name, false, nullptr, memory.get());
    OIIO::ImageSpec config, spec;
    config.attribute("oiio:UnassociatedAlpha", 1);
    if (!in || !in->supports("ioproxy") || !in->set_ioproxy(memory.get()) || !in->open(name, spec, config)) {
      error = in ? in->geterror() : OIIO::geterror();
      if (error.empty()) error = "cannot decode the embedded '" + format + "' image";
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(in), std::move(memory));
  }

  bool encode(const DisplayImageFile& image, std::vector<unsigned char>& out, std::string& error) const override {
    return encode_display(image, out, error);
  }

  bool write_exr(const std::string& path, const LayeredImage& image, const ImageMetadata& metadata,
                 const ExrSettings& exr, std::string& error) const override {
    return write_exr_layers(path, image, metadata, exr, error);
  }

  std::unique_ptr<ExrBandWriter> open_exr(const std::string& path, const LayeredImage& layout,
                                          const ImageMetadata& metadata, const ExrSettings& exr,
                                          std::string& error) const override {
    return open_exr_bands(path, layout, metadata, exr, error);
  }

  std::unique_ptr<TextureSystem> texture_system(uint64_t max_bytes) const override {
    return make_texture_system(max_bytes);
  }
};

}  // namespace
}  // namespace pt

extern "C" {

__attribute__((visibility("default"))) const char* pt_image_library_abi() {
  static const std::string abi = pt::image_library_abi();
  return abi.c_str();
}

__attribute__((visibility("default"))) const pt::ImageLibrary* pt_image_library() {
  static const pt::OiioLibrary library;
  return &library;
}

}  // extern "C"
