#include "imagelib/oiio/exr_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include <Imath/half.h>
#include <cpuid.h>
#include <immintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "io/exr_bands.h"

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

// One layer of a part as packed for the file: its float values (its
// channels interleaved), where its channels go in a packed pixel (one after
// another), and whether they are stored as half.
struct PackedLayer {
  const float* values;
  std::size_t channels, offset;
  bool half;
};

// The layers of a part, in order, and the bytes of a packed pixel:
// OpenImageIO's "native" layout, each channel in its file type.
std::vector<PackedLayer> packed_layers(const std::vector<const ImageLayer*>& layers, std::size_t& pixel_bytes) {
  std::vector<PackedLayer> packed;
  pixel_bytes = 0;
  for (const ImageLayer* layer : layers) {
    const bool half = layer->type == ChannelType::Half;
    packed.push_back({layer->values.data(), layer->channels.size(), pixel_bytes, half});
    pixel_bytes += layer->channels.size() * (half ? sizeof(uint16_t) : sizeof(float));
  }
  return packed;
}

// `n` pixels of `channels` floats each (`v`, interleaved) as half bits into
// `o`, a pixel's halves one after another and pixels `step` bytes apart,
// rounded to nearest even: Imath's conversion (OpenImageIO's), in software
// since the build targets plain x86-64, or the CPU's F16C one, which rounds
// the same way (finite values, infinities, subnormals; NaNs, whose payloads
// the two treat differently, go through Imath).
void pack_halves_soft(const float* v, std::size_t channels, std::size_t n, unsigned char* o, std::size_t step) {
  for (std::size_t x = 0; x < n; ++x)
    for (std::size_t c = 0; c < channels; ++c) {
      const uint16_t bits = Imath::half(v[x * channels + c]).bits();
      std::memcpy(o + x * step + c * sizeof bits, &bits, sizeof bits);
    }
}

__attribute__((target("f16c"))) void pack_halves_f16c(const float* v, std::size_t channels, std::size_t n,
                                                      unsigned char* o, std::size_t step) {
  for (std::size_t x = 0; x < n; ++x)
    for (std::size_t c = 0; c < channels; ++c) {
      const float f = v[x * channels + c];
      // _mm_cvtps_ph on one lane: _cvtss_sh is a macro with a compound literal in clang's header (-Wpedantic).
      const uint16_t bits = std::isnan(f) ? Imath::half(f).bits()
                                          : static_cast<uint16_t>(_mm_extract_epi16(
                                                _mm_cvtps_ph(_mm_set_ss(f), _MM_FROUND_TO_NEAREST_INT), 0));
      std::memcpy(o + x * step + c * sizeof bits, &bits, sizeof bits);
    }
}

// F16C: its CPUID bit, and the AVX state the OS must save for VEX code
// (__builtin_cpu_supports("avx") checks both the CPU and the OS). Asked of
// CPUID because clang 14 (the fuzz and sanitizer builds) does not know
// __builtin_cpu_supports("f16c").
bool cpu_has_f16c() {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  return __builtin_cpu_supports("avx") && __get_cpuid(1, &eax, &ebx, &ecx, &edx) != 0 && (ecx & bit_F16C) != 0;
}

void pack_halves(const float* v, std::size_t channels, std::size_t n, unsigned char* o, std::size_t step) {
  static const bool f16c = cpu_has_f16c();
  if (f16c) {
    pack_halves_f16c(v, channels, n, o, step);
  } else {
    pack_halves_soft(v, channels, n, o, step);
  }
}

// `n` pixels of `channels` floats each (`v`) into `o`, pixels `step` bytes
// apart; the usual counts with a copy of a fixed size (inlined).
template <std::size_t kChannels>
void copy_pixels(const float* v, std::size_t n, unsigned char* o, std::size_t step) {
  for (std::size_t x = 0; x < n; ++x) std::memcpy(o + x * step, v + x * kChannels, kChannels * sizeof(float));
}
void copy_floats(const float* v, std::size_t channels, std::size_t n, unsigned char* o, std::size_t step) {
  switch (channels) {
    case 1: return copy_pixels<1>(v, n, o, step);
    case 3: return copy_pixels<3>(v, n, o, step);
    case 4: return copy_pixels<4>(v, n, o, step);
    default:
      for (std::size_t x = 0; x < n; ++x) std::memcpy(o + x * step, v + x * channels, channels * sizeof(float));
  }
}

// Rows [y0, y1) of the data window packed into `out`, channels interleaved
// in their file types (halves rounded to nearest even, as OpenImageIO's
// conversion does), rows in parallel, a layer's channels of a pixel at a
// time (they are next to each other on both sides). Writing this "native"
// data lets OpenImageIO hand it to OpenEXR as it is: no float image of every
// channel interleaved, and no conversion copy of it.
void pack_rows(const LayeredImage& image, const std::vector<PackedLayer>& layers, std::size_t pixel_bytes, int y0,
               int y1, unsigned char* out) {
  const auto width = static_cast<std::size_t>(image.width);
  tbb::parallel_for(tbb::blocked_range<int>(y0, y1), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      const std::size_t first = static_cast<std::size_t>(y) * width;
      unsigned char* row = out + static_cast<std::size_t>(y - y0) * width * pixel_bytes;
      for (const PackedLayer& l : layers) {
        const float* v = l.values + first * l.channels;
        unsigned char* o = row + l.offset;
        if (l.half) {
          pack_halves(v, l.channels, width, o, pixel_bytes);
        } else {
          copy_floats(v, l.channels, width, o, pixel_bytes);
        }
      }
    }
  });
}

// Writes the pixels of a part holding `layers` (opened), band by band.
bool write_part(OIIO::ImageOutput& out, const LayeredImage& image, const std::vector<const ImageLayer*>& layers) {
  std::size_t pixel_bytes = 0;
  const std::vector<PackedLayer> packed = packed_layers(layers, pixel_bytes);
  const std::size_t row_bytes = pixel_bytes * static_cast<std::size_t>(image.width);
  const int band = exr_band_rows(row_bytes, image.height);  // the memory pre-flight counts this band
  std::vector<unsigned char> buffer(static_cast<std::size_t>(band) * row_bytes);
  for (int y0 = 0; y0 < image.height; y0 += band) {
    const int y1 = std::min(image.height, y0 + band);
    pack_rows(image, packed, pixel_bytes, y0, y1, buffer.data());
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

// Every layer of `image`, in order: the layers of its one part.
std::vector<const ImageLayer*> every_layer(const LayeredImage& image) {
  std::vector<const ImageLayer*> layers;
  for (const ImageLayer& layer : image.layers) layers.push_back(&layer);
  return layers;
}

// The one part of an EXR written band by band (ImageLibrary::open_exr).
class OiioExrBandWriter final : public ExrBandWriter {
 public:
  OiioExrBandWriter(std::unique_ptr<OIIO::ImageOutput> out, std::size_t row_bytes)
      : out_(std::move(out)), row_bytes_(row_bytes) {}

  std::size_t row_bytes() const override { return row_bytes_; }

  void pack(const LayeredImage& band, unsigned char* out) const override {
    std::size_t pixel_bytes = 0;
    const std::vector<PackedLayer> packed = packed_layers(every_layer(band), pixel_bytes);
    pack_rows(band, packed, pixel_bytes, 0, band.height, out);
  }

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
  // CIE xy of the Rec.709 red, green and blue primaries and of D65.
  static const float kRec709[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), kRec709);
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
  std::size_t pixel_bytes = 0;  // the layout's layers hold no values: only the sizes are read
  packed_layers(layers, pixel_bytes);
  return std::make_unique<OiioExrBandWriter>(std::move(out), pixel_bytes * static_cast<std::size_t>(layout.width));
}

}  // namespace pt
