#include "bench_common.h"

#include <iostream>

#include "scene/loader.h"

namespace pt::bench {

std::optional<LoadedScene> load(const std::string& path, AccelKind accel, WorkerPool& pool) {
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
  t = Clock::now();
  BuildOptions options;
  options.accel = accel;
  out.scene = build_render_scene(out.desc, options, pool, diag);
  if (!out.scene) {
    std::cerr << diag.format();
    return std::nullopt;
  }
  out.build_seconds = seconds_since(t);
  return out;
}

IntegratorSettings settings_for(const SceneDescription& desc, int spp, int first_sample, uint64_t seed) {
  IntegratorSettings s;
  s.max_depth = desc.render.max_depth;
  s.filter = desc.render.filter;
  s.clamp = desc.render.clamp;
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

}  // namespace pt::bench
