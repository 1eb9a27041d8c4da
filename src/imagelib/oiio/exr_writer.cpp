#include "imagelib/oiio/exr_writer.h"

#include <algorithm>
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "io/exr_bands.h"
#include "io/exr_pack.h"

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

// Rows [y0, y1) of the data window packed into `out`, channels interleaved
// in their file types (halves rounded to nearest even, as OpenImageIO's
// conversion does), rows in parallel, a layer's channels of a pixel at a
// time (they are next to each other on both sides). Writing this "native"
// data lets OpenImageIO hand it to OpenEXR as it is: no float image of every
// channel interleaved, and no conversion copy of it.
void pack_rows(const LayeredImage& image, const std::vector<const ImageLayer*>& layers, const PackedLayout& packed,
               int y0, int y1, unsigned char* out) {
  const auto width = static_cast<std::size_t>(image.width);
  tbb::parallel_for(tbb::blocked_range<int>(y0, y1), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      const std::size_t first = static_cast<std::size_t>(y) * width;
      unsigned char* row = out + static_cast<std::size_t>(y - y0) * width * packed.pixel_bytes;
      for (std::size_t i = 0; i < layers.size(); ++i) {
        const PackedLayer& l = packed.layers[i];
        const float* v = layers[i]->values.data() + first * l.channels;
        (l.half ? pack_halves : pack_floats)(v, l.channels, l.channels, width, row + l.offset, packed.pixel_bytes);
      }
    }
  });
}

// Writes the pixels of a part holding `layers` (opened), band by band.
bool write_part(OIIO::ImageOutput& out, const LayeredImage& image, const std::vector<const ImageLayer*>& layers) {
  const PackedLayout packed = packed_layout(layers);
  const std::size_t row_bytes = packed.pixel_bytes * static_cast<std::size_t>(image.width);
  const int band = exr_band_rows(row_bytes, image.height);  // the memory pre-flight counts this band
  std::vector<unsigned char> buffer(static_cast<std::size_t>(band) * row_bytes);
  for (int y0 = 0; y0 < image.height; y0 += band) {
    const int y1 = std::min(image.height, y0 + band);
    pack_rows(image, layers, packed, y0, y1, buffer.data());
    if (!out.write_scanlines(image.y + y0, image.y + y1, 0, OIIO::TypeUnknown, buffer.data())) return false;
  }
  return true;
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

// The one part of an EXR written band by band (ImageLibrary::open_exr).
class OiioExrBandWriter final : public ExrBandWriter {
 public:
  OiioExrBandWriter(std::unique_ptr<OIIO::ImageOutput> out, std::size_t row_bytes)
      : out_(std::move(out)), row_bytes_(row_bytes) {}

  std::size_t row_bytes() const override { return row_bytes_; }

  bool write(int y0, int y1, const unsigned char* packed, std::string& error) override {
    if (out_->write_scanlines(y0, y1, 0, OIIO::TypeUnknown, packed)) return true;
    error = out_->geterror();
    return false;
  }

  bool close(std::string& error) override {
    if (out_->close()) return true;
    error = out_->geterror();
    return false;
  }

 private:
  std::unique_ptr<OIIO::ImageOutput> out_;
  std::size_t row_bytes_;
};

}  // namespace

void add_image_metadata(OIIO::ImageSpec& spec, const ImageMetadata& metadata, bool typed) {
  for (const auto& [name, value] : metadata.strings) spec.attribute(name, value);
  if (!typed) return;
  for (const auto& [name, value] : metadata.ints) spec.attribute(name, value);
  for (const auto& [name, value] : metadata.floats) spec.attribute(name, value);
  for (const auto& [name, value] : metadata.matrices) spec.attribute(name, OIIO::TypeMatrix44, value.data());
  spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), kExrChromaticities.data());
}

bool write_exr_layers(const std::string& path, const LayeredImage& image, const ImageMetadata& metadata,
                      const ExrSettings& exr, std::string& error) {
  if (!check_layers(image, error)) return false;
  // OpenEXR compresses blocks of rows on its own threads: as many as --threads (process-wide, set per write).
  OIIO::attribute("exr_threads", exr.threads > 0 ? exr.threads : 0);
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
    ok = ok && write_part(*out, image, parts[p]);
  }
  if (!ok) error = out->geterror();
  if (!out->close() && ok) {
    error = out->geterror();
    ok = false;
  }
  return ok;
}

std::unique_ptr<ExrBandWriter> open_exr_bands(const std::string& path, const LayeredImage& layout,
                                              const ImageMetadata& metadata, const ExrSettings& exr,
                                              std::string& error) {
  if (layout.layers.empty() || layout.pixel_count() == 0) {
    error = "the image has no pixels";
    return nullptr;
  }
  OIIO::attribute("exr_threads", exr.threads > 0 ? exr.threads : 0);  // as write_exr_layers
  const std::vector<const ImageLayer*> layers = every_layer(layout);
  ExrSettings one_part = exr;
  one_part.multipart = false;
  const OIIO::ImageSpec spec = part_spec(layout, layers, metadata, one_part);
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) {
    error = OIIO::geterror();
    return nullptr;
  }
  if (!out->open(path, spec)) {
    error = out->geterror();
    return nullptr;
  }
  // The layout's layers hold no values: only their channels and types are read.
  return std::make_unique<OiioExrBandWriter>(std::move(out),
                                             packed_layout(layers).pixel_bytes * static_cast<std::size_t>(layout.width));
}

}  // namespace pt
