#include "io/exr_layers.h"

namespace pt {

void add_image_metadata(OIIO::ImageSpec& spec, const ImageMetadata& metadata, bool typed) {
  for (const auto& [name, value] : metadata.strings) spec.attribute(name, value);
  if (!typed) return;
  for (const auto& [name, value] : metadata.ints) spec.attribute(name, value);
  for (const auto& [name, value] : metadata.floats) spec.attribute(name, value);
  for (const auto& [name, value] : metadata.matrices) spec.attribute(name, OIIO::TypeMatrix44, value.data());
  // CIE xy of the Rec.709 red, green and blue primaries and of D65.
  static const float kRec709[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), kRec709);
}

bool write_exr_layers(const std::string& path, const LayeredImage& image, const ImageMetadata& metadata,
                      std::string& error) {
  std::size_t nchannels = 0;
  for (const ImageLayer& layer : image.layers) {
    nchannels += layer.channels.size();
    if (layer.values.size() != image.pixel_count() * layer.channels.size()) {
      error = "layer '" + layer.name + "' has " + std::to_string(layer.values.size()) + " values, expected " +
              std::to_string(image.pixel_count() * layer.channels.size());
      return false;
    }
  }
  if (nchannels == 0 || image.pixel_count() == 0) {
    error = "the image has no pixels";
    return false;
  }
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) {
    error = OIIO::geterror();
    return false;
  }
  OIIO::ImageSpec spec(image.width, image.height, static_cast<int>(nchannels), OIIO::TypeDesc::FLOAT);
  spec.x = image.x;
  spec.y = image.y;
  spec.full_x = 0;
  spec.full_y = 0;
  spec.full_width = image.full_width;
  spec.full_height = image.full_height;
  spec.channelnames.clear();
  spec.channelformats.clear();
  bool any_half = false;
  for (const ImageLayer& layer : image.layers)
    for (const std::string& name : layer.channels) {
      spec.channelnames.push_back(name);
      const bool half = layer.type == ChannelType::Half;
      any_half = any_half || half;
      spec.channelformats.push_back(half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    }
  spec.alpha_channel = 3;
  if (!any_half) spec.channelformats.clear();  // one format for all: the plain case
  spec.attribute("Software", "pathtracer " PT_VERSION);
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  add_image_metadata(spec, metadata, true);

  // Interleave every layer's channels into one float buffer; OpenImageIO
  // converts each channel to its format.
  std::vector<float> pixels(image.pixel_count() * nchannels);
  std::size_t first = 0;
  for (const ImageLayer& layer : image.layers) {
    const std::size_t n = layer.channels.size();
    for (std::size_t i = 0; i < image.pixel_count(); ++i)
      for (std::size_t c = 0; c < n; ++c) pixels[i * nchannels + first + c] = layer.values[i * n + c];
    first += n;
  }
  if (!out->open(path, spec)) {
    error = out->geterror();
    return false;
  }
  bool ok = out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  if (!ok) error = out->geterror();
  if (!out->close() && ok) {
    error = out->geterror();
    ok = false;
  }
  return ok;
}

}  // namespace pt
