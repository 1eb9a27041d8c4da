#include "bench_common.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "scene/loader.h"

namespace pt::bench {

std::optional<LoadedScene> load(const std::string& path, AccelKind accel, const SettingsOverrides& overrides,
                                WorkerPool& pool) {
  LoadedScene out;
  Diagnostics diag;
  auto t = Clock::now();
  std::optional<SceneDescription> desc = load_scene(path, LoadOptions{}, diag);
  if (!desc) {
    std::cerr << diag.format();
    return std::nullopt;
  }
  out.load_seconds = seconds_since(t);
  out.desc = std::move(*desc);
  if (!resolve_render_settings(out.desc, overrides, out.settings, diag)) {
    std::cerr << diag.format();
    return std::nullopt;
  }
  t = Clock::now();
  out.scene = build_render_scene(out.desc, out.settings.build_options(accel), pool, diag);
  if (!out.scene) {
    std::cerr << diag.format();
    return std::nullopt;
  }
  out.build_seconds = seconds_since(t);
  return out;
}

IntegratorSettings settings_for(const LoadedScene& scene, int spp, int first_sample, uint64_t seed) {
  IntegratorSettings s = scene.settings.integration;
  s.spp = spp;
  s.first_sample = first_sample;
  s.seed = seed;
  return s;
}

ImageError compare(const Image& image, const Image& reference) {
  ImageError e;
  double sq = 0, rel = 0, sum[3] = {0, 0, 0}, ref_sum[3] = {0, 0, 0};
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = image.pixels[i][c], r = reference.pixels[i][c];
      sq += (x - r) * (x - r);
      rel += (x - r) * (x - r) / (r * r + 0.01);
      sum[c] += x;
      ref_sum[c] += r;
    }
  }
  const double n = 3.0 * static_cast<double>(image.pixels.size());
  e.rmse = std::sqrt(sq / n);
  e.relmse = rel / n;
  for (int c = 0; c < 3; ++c) e.mean_ratio[c] = ref_sum[c] > 0 ? sum[c] / ref_sum[c] : 0.0;
  return e;
}

namespace {

enum Region { kLightInterior, kLightEdge, kEdge, kSmooth, kRegions };

double luminance(const RGB& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
bool is_light(const RGB& c) { return std::max({c.r, c.g, c.b}) > kLightLevel; }

// Whether pixel (x, y) and its 8 neighbours inside the image are all light
// (all = true) or whether any pixel within `radius` is (all = false).
bool light_around(const Image& ref, int x, int y, int radius, bool all) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int u = x + dx, v = y + dy;
      if (u < 0 || v < 0 || u >= ref.width || v >= ref.height) continue;
      if (is_light(ref.at(u, v)) != all) return !all;
    }
  return all;
}

Region region_of(const Image& ref, int x, int y) {
  if (light_around(ref, x, y, 1, true)) return kLightInterior;
  if (light_around(ref, x, y, 2, false)) return kLightEdge;
  const double l = luminance(ref.at(x, y));
  const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
  for (int k = 0; k < 4; ++k) {
    if (nx[k] < 0 || ny[k] < 0 || nx[k] >= ref.width || ny[k] >= ref.height) continue;
    const double m = luminance(ref.at(nx[k], ny[k]));
    if (std::fabs(l - m) > 0.25 * std::max(l, m)) return kEdge;
  }
  return kSmooth;
}

double squared_error(const RGB& x, const RGB& r) {
  const double d[3] = {x.r - r.r, x.g - r.g, x.b - r.b};
  return (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / 3.0;
}

}  // namespace

std::vector<RegionError> error_breakdown(const Image& image, const Image& reference) {
  static constexpr const char* kNames[kRegions] = {"light interior", "light edge", "edge", "smooth"};
  double sq[kRegions] = {}, count[kRegions] = {}, total = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      const Region r = region_of(reference, x, y);
      const double e = squared_error(image.at(x, y), reference.at(x, y));
      sq[r] += e;
      count[r] += 1;
      total += e;
    }
  const double pixels = static_cast<double>(reference.width) * reference.height;
  std::vector<RegionError> out;
  for (int r = 0; r < kRegions; ++r)
    out.push_back({kNames[r], count[r] / pixels, total > 0 ? sq[r] / total : 0,
                   count[r] > 0 ? std::sqrt(sq[r] / count[r]) : 0});
  return out;
}

Image error_map(const Image& image, const Image& reference) {
  Image out(reference.width, reference.height);
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    const float e = static_cast<float>(squared_error(image.pixels[i], reference.pixels[i]));
    out.pixels[i] = RGB(e, e, e);
  }
  return out;
}

}  // namespace pt::bench
