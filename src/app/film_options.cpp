#include "app/film_options.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>
#include <string>
#include <thread>

#include "app/options.h"
#include "app/shard.h"
#include "io/exr_bands.h"
#include "io/exr_pack.h"
#include "io/image_io.h"

namespace pt {
namespace {

std::string frame(int width, int height) { return std::to_string(width) + "x" + std::to_string(height) + " frame"; }

}  // namespace

bool film_aovs(const Options& o, const IntegratorInfo& integrator, std::vector<AovRequest>& out, ChannelType& beauty,
               std::string& error) {
  out.clear();
  beauty = ChannelType::Float;
  if (o.replaying()) {  // a replay reports every AOV of its one sample (they draw no random numbers)
    for (const AovInfo& info : aov_catalogue())
      if (integrator.produces(info.type))
        out.push_back({info.type, info.default_type, info.accumulation == Accumulation::Ranked ? 1 : 0});
    return true;
  }
  std::string why;
  if (!o.aov.empty() &&
      (!parse_aov_list(o.aov, out, beauty, why, o.cryptomatte_levels) || !integrator.check_aovs(out, why))) {
    error = "--aov: " + why;
    return false;
  }
  return true;
}

bool region_window(const Options& o, int width, int height, PixelRect& out, std::string& error) {
  out = {0, 0, width, height};
  if (o.replaying()) {
    const int x = o.replay[0], y = o.replay[1];
    if (x < 0 || y < 0 || x >= width || y >= height) {
      error = o.replay_option + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is not inside the " +
              frame(width, height);
      return false;
    }
    out = {x, y, x + 1, y + 1};
  } else if (!o.crop.empty()) {
    const std::vector<double>& c = o.crop;
    if (!(0.0 <= c[0] && c[0] < c[2] && c[2] <= 1.0 && 0.0 <= c[1] && c[1] < c[3] && c[3] <= 1.0)) {
      error = "--crop: need 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1";
      return false;
    }
    out = {static_cast<int>(std::floor(c[0] * width)), static_cast<int>(std::floor(c[1] * height)),
           static_cast<int>(std::ceil(c[2] * width)), static_cast<int>(std::ceil(c[3] * height))};
  } else if (!o.crop_px.empty()) {
    const std::vector<int>& c = o.crop_px;
    if (c[0] > width || c[1] > height || c[2] > width || c[3] > height) {  // also keeps X + W from overflowing
      error = "--crop-px: " + std::to_string(c[2]) + "x" + std::to_string(c[3]) + " at (" + std::to_string(c[0]) +
              ", " + std::to_string(c[1]) + ") is not inside the " + frame(width, height);
      return false;
    }
    out = {c[0], c[1], c[0] + c[2], c[1] + c[3]};
  }
  if (out.x0 < 0 || out.y0 < 0 || out.empty() || out.x1 > width || out.y1 > height) {
    error = "the crop [" + std::to_string(out.x0) + ", " + std::to_string(out.x1) + ") x [" + std::to_string(out.y0) +
            ", " + std::to_string(out.y1) + ") is not inside the " + frame(width, height);
    return false;
  }
  return true;
}

bool crop_window(const Options& o, int width, int height, PixelRect& out, std::string& error) {
  if (!region_window(o, width, height, out, error)) return false;
  if (o.tile.empty() || o.replaying()) return true;
  const std::optional<Fraction> tile = parse_fraction(o.tile, error);
  if (!tile) return false;
  const PixelRect region = out;
  out = tile_of(region, *tile);
  if (out.empty()) {
    error = "--tile " + o.tile + ": the region has " + std::to_string(region.height()) + " rows, fewer than " +
            std::to_string(tile->n) + " tiles";
    return false;
  }
  return true;
}

std::size_t film_bytes_per_pixel(const std::vector<AovRequest>& aovs) {
  std::size_t bytes = sizeof(PixelSum);
  for (const AovRequest& r : aovs)
    bytes += sizeof(ExactSum) * static_cast<std::size_t>(aov_state_sums(r)) +
             sizeof(double) * static_cast<std::size_t>(aov_state_values(r));
  return bytes;
}

std::size_t layer_bytes_per_pixel(const std::vector<AovRequest>& aovs) {
  std::size_t channels = 4;  // R, G, B, A
  for (const AovRequest& r : aovs) channels += static_cast<std::size_t>(aov_channel_count(r));
  return channels * sizeof(float);
}

uint64_t writer_bytes(const std::vector<AovRequest>& aovs, ChannelType beauty, const std::vector<std::string>& outputs,
                      const ExrSettings& exr, int width, int height) {
  // The EXR's layers as the film lays them out (a film of no pixels: the
  // layers' channels and types, no values), each layer's packed pixel.
  const LayeredImage shape = Film(0, 0, PixelRect{}, aovs).layer_layout(beauty, PixelRect{});
  std::size_t part = 0, all = 0;  // the largest part's packed pixel; every part's
  for (const ImageLayer& layer : shape.layers) {
    const std::size_t bytes = packed_pixel_bytes(layer);
    all += bytes;
    part = exr.multipart ? std::max(part, bytes) : all;
  }
  const unsigned hardware = std::thread::hardware_concurrency();
  const int threads = exr.threads > 0 ? exr.threads : static_cast<int>(std::max(1u, hardware));
  const uint64_t exr_bytes =
      exr_band_bytes(part, width, height) +
      exr_line_buffer_bytes(all * static_cast<std::size_t>(std::max(0, width)), height,
                            exr_block_rows(exr.compression), threads);
  const uint64_t pixels = static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
  uint64_t largest = 0;
  for (const std::string& path : outputs) {
    const uint64_t own = is_exr_path(path) ? exr_bytes : pixels * (3 * sizeof(float) + 3 * sizeof(uint8_t));  // RGB, codes
    largest = std::max(largest, own);
  }
  return largest;
}

bool estimate_render_memory(const Options& o, const SceneDescription& scene, int width, int height,
                            const std::vector<AovRequest>& aovs, ChannelType beauty, MemoryEstimate& out,
                            std::string& error) {
  PixelRect crop;
  if (!crop_window(o, width, height, crop, error)) return false;
  const uint64_t pixels = static_cast<uint64_t>(crop.width()) * static_cast<uint64_t>(crop.height());
  AccelKind accel = AccelKind::Bvh;
  parse_accel_kind(o.accel, accel);  // CLI11 checked the name
  const uint64_t cache = o.texture_cache.empty() ? TextureCache::kDefaultBytes
                                                : parse_byte_size(o.texture_cache).value_or(TextureCache::kDefaultBytes);
  const PixelBytes buffers = {film_bytes_per_pixel(aovs), layer_bytes_per_pixel(aovs),
                              writer_bytes(aovs, beauty, o.outputs, {o.exr_compression, o.multipart, o.threads},
                                           crop.width(), crop.height())};
  out = estimate_memory(scene, pixels, buffers, o.resume.empty() ? 1 : 2, accel, cache);
  out.baseline = resident_bytes();
  out.peak_so_far = peak_resident_bytes();
  out.reusable = std::min(free_heap_bytes(), out.baseline);
  return true;
}

std::string replay_hint(const NonFiniteReport& report) {
  if (!report.has_first) return {};
  return "; to replay the first, run this command again with --pixel " + std::to_string(report.x) + "," +
         std::to_string(report.y) + " --sample " + std::to_string(report.sample);
}

std::string replay_text(const Film& film, int x, int y, int sample) {
  const NonFiniteReport& non_finite = film.non_finite();
  const RGB v = non_finite.total() > 0 ? non_finite.value : film.sum(x, y).value();
  std::ostringstream out;
  out << std::setprecision(9) << "replay pixel (" << x << ", " << y << ") sample " << sample << ": radiance " << v.r
      << " " << v.g << " " << v.b << '\n';
  // The pixel is the mean of its samples weighted by this (1 for the box filter).
  out << "  filter weight: " << film.sum(x, y).weight.value() << '\n';
  for (const AovRequest& r : film.aovs()) {
    if (r.type == AovType::Samples || r.type == AovType::Variance) continue;
    out << "  " << aov_info(r.type).name << ":";
    const std::vector<float> values = film.aov_value(r.type, x, y);
    if (r.ranks > 0)  // Cryptomatte: the id (as the manifest writes it) of what the sample hit, or none
      out << ' ' << (values[0] != 0.0f ? cryptomatte_hex(values[0]) : std::string("none"));
    else
      for (float c : values) out << ' ' << c;
    out << '\n';
  }
  return out.str();
}

}  // namespace pt
