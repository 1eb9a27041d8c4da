// Helpers for the path integrator's tests: render a description, and the
// statistics the tests compare images with.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "render/film/film.h"
#include "render/integrators/integrator.h"
#include "test_scenes.h"

namespace pt::test {

// A microfacet material (conductor, rough dielectric, coated diffuse) with
// alpha_x, alpha_y given directly (remaproughness off) and index 1.5.
inline MaterialDesc microfacet_desc(MaterialType type, float ax, float ay) {
  MaterialDesc m;
  m.type = type;
  m.remap_roughness = false;
  m.uroughness.value = ax;
  m.vroughness.value = ay;
  m.ior = 1.5f;
  return m;
}

inline IntegratorSettings path_settings(int spp, int max_depth = 64, uint64_t seed = 0) {
  IntegratorSettings s;
  s.spp = spp;
  s.max_depth = max_depth;
  s.seed = seed;
  return s;
}

// A render's image and its film's report of non-finite samples. The render
// loop adds a NaN or infinite sample as black, so the image alone cannot show
// one: a test that promises "no NaN" checks `non_finite.total() == 0`.
struct Rendered {
  Image image;
  NonFiniteReport non_finite;
};

// Renders `d` with the named integrator; an empty image (and a test failure) on error.
inline Rendered render_film(const SceneDescription& d, const std::string& integrator,
                            const IntegratorSettings& settings, int threads = 2, const BuildOptions& options = {}) {
  WorkerPool pool(threads);
  auto scene = build(d, pool, options);
  if (!scene) return {};
  std::string error;
  auto in = make_integrator(integrator, settings, error);
  EXPECT_TRUE(in) << error;
  if (!in) return {};
  Film film(scene->width, scene->height);
  in->render(*scene, film, pool);
  return {film.image(), film.non_finite()};
}

inline Image render_with(const SceneDescription& d, const std::string& integrator, const IntegratorSettings& settings,
                         int threads = 2, const BuildOptions& options = {}) {
  return render_film(d, integrator, settings, threads, options).image;
}

inline Image render_path(const SceneDescription& d, const IntegratorSettings& settings, int threads = 2) {
  return render_with(d, "path", settings, threads);
}

// Mean and standard deviation of one channel (or of all three, channel = -1)
// over the pixels selected by `use`.
struct Stats {
  double mean = 0, stddev = 0;
  std::size_t count = 0;
};

template <class Use>
Stats channel_stats(const Image& img, int channel, Use use) {
  double sum = 0, sum2 = 0;
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      if (!use(x, y)) continue;
      for (int c = 0; c < 3; ++c) {
        if (channel >= 0 && c != channel) continue;
        const double v = img.at(x, y)[c];
        sum += v;
        sum2 += v * v;
        ++n;
      }
    }
  }
  Stats s;
  s.count = n;
  if (n == 0) return s;
  s.mean = sum / n;
  s.stddev = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
  return s;
}

inline Stats image_stats(const Image& img) {
  return channel_stats(img, -1, [](int, int) { return true; });
}

// Root mean square difference over all pixels and channels.
inline double rmse(const Image& a, const Image& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(a.pixels[i][c]) - b.pixels[i][c];
      sum += d * d;
    }
  return std::sqrt(sum / (3.0 * static_cast<double>(a.pixels.size())));
}

}  // namespace pt::test
