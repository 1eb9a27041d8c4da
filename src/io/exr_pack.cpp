#include "io/exr_pack.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include <Imath/half.h>
#include <cpuid.h>
#include <immintrin.h>

namespace pt {

namespace {

// Halves rounded to nearest even: Imath's conversion (OpenImageIO's), in
// software since the build targets plain x86-64, or the CPU's F16C one, which
// rounds the same way (finite values, infinities, subnormals; NaNs, whose
// payloads the two treat differently, go through Imath).
void pack_halves_soft(const float* v, std::size_t in_step, std::size_t channels, std::size_t n, unsigned char* o,
                      std::size_t out_step) {
  for (std::size_t x = 0; x < n; ++x)
    for (std::size_t c = 0; c < channels; ++c) {
      const uint16_t bits = Imath::half(v[x * in_step + c]).bits();
      std::memcpy(o + x * out_step + c * sizeof bits, &bits, sizeof bits);
    }
}

__attribute__((target("f16c"))) void pack_halves_f16c(const float* v, std::size_t in_step, std::size_t channels,
                                                      std::size_t n, unsigned char* o, std::size_t out_step) {
  for (std::size_t x = 0; x < n; ++x)
    for (std::size_t c = 0; c < channels; ++c) {
      const float f = v[x * in_step + c];
      // _mm_cvtps_ph on one lane: _cvtss_sh is a macro with a compound literal in clang's header (-Wpedantic).
      const uint16_t bits = std::isnan(f) ? Imath::half(f).bits()
                                          : static_cast<uint16_t>(_mm_extract_epi16(
                                                _mm_cvtps_ph(_mm_set_ss(f), _MM_FROUND_TO_NEAREST_INT), 0));
      std::memcpy(o + x * out_step + c * sizeof bits, &bits, sizeof bits);
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

// One channel of `n` pixels (`step` floats apart) into a line of halves, 8
// at a time with F16C, a group holding a NaN through Imath (pack_halves_f16c).
__attribute__((target("avx,f16c"))) void line_halves_f16c(const float* v, std::size_t step, std::size_t n,
                                                           unsigned char* o) {
  std::size_t x = 0;
  for (; x + 8 <= n; x += 8) {
    const float* p = v + x * step;
    const __m256 f = _mm256_setr_ps(p[0], p[step], p[2 * step], p[3 * step], p[4 * step], p[5 * step], p[6 * step],
                                    p[7 * step]);
    if (_mm256_movemask_ps(_mm256_cmp_ps(f, f, _CMP_UNORD_Q)) != 0) {
      for (std::size_t i = 0; i < 8; ++i) {
        const uint16_t bits = Imath::half(p[i * step]).bits();
        std::memcpy(o + (x + i) * sizeof bits, &bits, sizeof bits);
      }
      continue;
    }
    _mm_storeu_si128(reinterpret_cast<__m128i*>(o + x * sizeof(uint16_t)), _mm256_cvtps_ph(f, _MM_FROUND_TO_NEAREST_INT));
  }
  pack_halves_f16c(v + x * step, step, 1, n - x, o + x * sizeof(uint16_t), sizeof(uint16_t));
}

// The usual counts with a copy of a fixed size (inlined).
template <std::size_t kChannels>
void copy_pixels(const float* v, std::size_t in_step, std::size_t n, unsigned char* o, std::size_t out_step) {
  for (std::size_t x = 0; x < n; ++x) std::memcpy(o + x * out_step, v + x * in_step, kChannels * sizeof(float));
}

}  // namespace

std::vector<const ImageLayer*> every_layer(const LayeredImage& image) {
  std::vector<const ImageLayer*> layers;
  for (const ImageLayer& layer : image.layers) layers.push_back(&layer);
  return layers;
}

std::size_t packed_pixel_bytes(const ImageLayer& layer) {
  return layer.channels.size() * (layer.type == ChannelType::Half ? sizeof(uint16_t) : sizeof(float));
}

PackedLayout packed_layout(const std::vector<const ImageLayer*>& layers) {
  PackedLayout packed;
  for (const ImageLayer* layer : layers) {
    packed.layers.push_back({layer->channels.size(), packed.pixel_bytes, layer->type == ChannelType::Half});
    packed.pixel_bytes += packed_pixel_bytes(*layer);
    packed.channels += layer->channels.size();
  }
  return packed;
}

PackedLayout packed_layout(const LayeredImage& image) { return packed_layout(every_layer(image)); }

namespace {
// A property of the CPU: asked once.
bool has_f16c() {
  static const bool f16c = cpu_has_f16c();
  return f16c;
}
}  // namespace

void pack_halves(const float* v, std::size_t in_step, std::size_t channels, std::size_t n, unsigned char* out,
                 std::size_t out_step) {
  const bool f16c = has_f16c();
  if (f16c) {
    pack_halves_f16c(v, in_step, channels, n, out, out_step);
  } else {
    pack_halves_soft(v, in_step, channels, n, out, out_step);
  }
}

void pack_floats(const float* v, std::size_t in_step, std::size_t channels, std::size_t n, unsigned char* out,
                 std::size_t out_step) {
  switch (channels) {
    case 1: return copy_pixels<1>(v, in_step, n, out, out_step);
    case 3: return copy_pixels<3>(v, in_step, n, out, out_step);
    case 4: return copy_pixels<4>(v, in_step, n, out, out_step);
    default:
      for (std::size_t x = 0; x < n; ++x) std::memcpy(out + x * out_step, v + x * in_step, channels * sizeof(float));
  }
}

void pack_pixels(const PackedLayout& layout, const float* values, std::size_t n, unsigned char* out) {
  std::size_t first = 0;  // the run's first channel in a pixel's values
  for (std::size_t i = 0; i < layout.layers.size();) {
    // Adjacent layers of one type are one run: their channels follow each other on both sides.
    const PackedLayer& l = layout.layers[i];
    std::size_t channels = 0;
    for (; i < layout.layers.size() && layout.layers[i].half == l.half; ++i) channels += layout.layers[i].channels;
    if (!l.half && channels == layout.channels) {  // floats only: the values are the packed bytes
      std::memcpy(out, values, n * layout.pixel_bytes);
      return;
    }
    (l.half ? pack_halves : pack_floats)(values + first, layout.channels, channels, n, out + l.offset,
                                         layout.pixel_bytes);
    first += channels;
  }
}

void pack_lines(const LineLayout& layout, const float* values, std::size_t x, std::size_t n, unsigned char* row) {
  const std::size_t step = layout.channels.size();
  const bool f16c = has_f16c();
  for (std::size_t c = 0; c < step; ++c) {
    const LineChannel& channel = layout.channels[c];
    const float* v = values + c;
    if (!channel.half) {
      unsigned char* o = row + channel.line + x * sizeof(float);
      for (std::size_t i = 0; i < n; ++i) std::memcpy(o + i * sizeof(float), v + i * step, sizeof(float));
    } else if (f16c) {
      line_halves_f16c(v, step, n, row + channel.line + x * sizeof(uint16_t));
    } else {
      pack_halves_soft(v, step, 1, n, row + channel.line + x * sizeof(uint16_t), sizeof(uint16_t));
    }
  }
}

}  // namespace pt
