#include "imagelib/oiio/exr_writer.h"

#include <vector>

namespace pt {

namespace {

// The header of a part holding `layers` (all of the image's, or one).
OIIO::ImageSpec part_spec(const LayeredImage& image, const std::vector<const ImageLayer*>& layers,
                          const ImageMetadata& metadata, const ExrSettings& exr) {
  int nchannels = 0;
  for (const ImageLayer* layer : layers) nchannels += static_cast<int>(layer->channels.size());
  OIIO::ImageSpec spec(image.width, image.height, nchannels, OIIO::TypeDesc::FLOAT);
  spec.x = image.x;
  spec.y = image.y;
  spec.full_x = 0;
  spec.full_y = 0;
  spec.full_width = image.full_width;
  spec.full_height = image.full_height;
  spec.channelnames.clear();
  spec.channelformats.clear();
  bool any_half = false;
  for (const ImageLayer* layer : layers)
    for (const std::string& name : layer->channels) {
      spec.channelnames.push_back(name);
      const bool half = layer->type == ChannelType::Half;
      any_half = any_half || half;
      spec.channelformats.push_back(half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    }
  spec.alpha_channel = layers.front()->name.empty() && layers.front()->channels.size() >= 4 ? 3 : -1;  // the beauty's A
  if (!any_half) spec.channelformats.clear();  // one format for all: the plain case
  spec.attribute("Software", "pathtracer " PT_VERSION);
  spec.attribute("compression", exr.compression);
  spec.attribute("oiio:ColorSpace", "Linear");
  if (exr.multipart) spec.attribute("oiio:subimagename", layers.front()->name.empty() ? "rgba" : layers.front()->name);
  add_image_metadata(spec, metadata, true);
  return spec;
}

// Every layer's channels interleaved into one float buffer, for a part
// holding `layers`; OpenImageIO converts each channel to its format.
std::vector<float> interleave(const LayeredImage& image, const std::vector<const ImageLayer*>& layers) {
  std::size_t nchannels = 0;
  for (const ImageLayer* layer : layers) nchannels += layer->channels.size();
  std::vector<float> pixels(image.pixel_count() * nchannels);
  std::size_t first = 0;
  for (const ImageLayer* layer : layers) {
    const std::size_t n = layer->channels.size();
    for (std::size_t i = 0; i < image.pixel_count(); ++i)
      for (std::size_t c = 0; c < n; ++c) pixels[i * nchannels + first + c] = layer->values[i * n + c];
    first += n;
  }
  return pixels;
}

bool check_layers(const LayeredImage& image, std::string& error) {
  std::size_t nchannels = 0;
  for (const ImageLayer& layer : image.layers) {
    nchannels += layer.channels.size();
    if (layer.channels.empty() || layer.values.size() != image.pixel_count() * layer.channels.size()) {
      error = "layer '" + layer.name + "' has " + std::to_string(layer.values.size()) + " values, expected " +
              std::to_string(image.pixel_count() * layer.channels.size());
      return false;
    }
  }
  if (nchannels == 0 || image.pixel_count() == 0) {
    error = "the image has no pixels";
    return false;
  }
  return true;
}

}  // namespace

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
                      const ExrSettings& exr, std::string& error) {
  if (!check_layers(image, error)) return false;
  // The parts: every layer in one, or one per layer.
  std::vector<std::vector<const ImageLayer*>> parts(exr.multipart ? image.layers.size() : 1);
  for (std::size_t l = 0; l < image.layers.size(); ++l) parts[exr.multipart ? l : 0].push_back(&image.layers[l]);
  std::vector<OIIO::ImageSpec> specs;
  for (const auto& part : parts) specs.push_back(part_spec(image, part, metadata, exr));

  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) {
    error = OIIO::geterror();
    return false;
  }
  if (specs.size() > 1 && !out->supports("multiimage")) {
    error = "this OpenImageIO cannot write multi-part EXR files";
    return false;
  }
  bool ok = out->open(path, static_cast<int>(specs.size()), specs.data());
  for (std::size_t p = 0; ok && p < parts.size(); ++p) {
    if (p > 0) ok = out->open(path, specs[p], OIIO::ImageOutput::AppendSubimage);
    ok = ok && out->write_image(OIIO::TypeDesc::FLOAT, interleave(image, parts[p]).data());
  }
  if (!ok) error = out->geterror();
  if (!out->close() && ok) {
    error = out->geterror();
    ok = false;
  }
  return ok;
}

}  // namespace pt
