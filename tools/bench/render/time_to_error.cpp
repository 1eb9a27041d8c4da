#include <algorithm>
#include <cstdio>
#include <string>

#include "io/image_io.h"

#include "measurements.h"

namespace pt::bench {

TimeToError time_to_error(const LoadedScene& s, const Image& reference, WorkerPool& pool, int pass_spp,
                          double target_rmse, double target_relmse, double max_seconds, uint64_t seed) {
  TimeToError out;
  Film film(s.scene->width, s.scene->height);
  double render_seconds = 0;
  int spp = 0;
  while (render_seconds < max_seconds && (out.seconds_to_rmse < 0 || out.seconds_to_relmse < 0)) {
    const auto integrator = s.settings.make_integrator(settings_for(s, pass_spp, spp, seed));
    const auto t = Clock::now();
    integrator->render(*s.scene, film, pool);
    render_seconds += seconds_since(t);
    spp += pass_spp;
    const ImageError e = compare(film.image(), reference);
    out.trace.push_back({spp, render_seconds, e.rmse, e.relmse});
    out.final_error = e;
    if (out.seconds_to_rmse < 0 && e.rmse < target_rmse) {
      out.seconds_to_rmse = render_seconds;
      out.spp_to_rmse = spp;
    }
    if (out.seconds_to_relmse < 0 && e.relmse < target_relmse) {
      out.seconds_to_relmse = render_seconds;
      out.spp_to_relmse = spp;
    }
  }
  return out;
}

ImageError converge(const LoadedScene& s, const Image& reference, WorkerPool& pool, int spp, int pass_spp,
                    uint64_t seed, const std::string& output, double* seconds, Image* result) {
  Film film(s.scene->width, s.scene->height);
  std::string error;
  *seconds = 0;
  for (int first = 0; first < spp; first += pass_spp) {
    const int n = std::min(pass_spp, spp - first);
    const auto integrator = s.settings.make_integrator(settings_for(s, n, first, seed));
    const auto t = Clock::now();
    integrator->render(*s.scene, film, pool);
    *seconds += seconds_since(t);
  }
  const Image image = film.image();
  if (!output.empty() && !write_image(output, image, DisplaySettings{}, error))
    std::fprintf(stderr, "bench_render: %s\n", error.c_str());
  if (result) *result = image;
  return compare(image, reference);
}

Throughput throughput(const LoadedScene& s, WorkerPool& pool, int spp, uint64_t seed) {
  Throughput out;
  const auto integrator = s.settings.make_integrator(settings_for(s, spp, 0, seed));
  Film film(s.scene->width, s.scene->height);
  const double cpu = process_cpu_seconds();
  const auto t = Clock::now();
  integrator->render(*s.scene, film, pool);
  out.seconds = seconds_since(t);
  out.cpu_seconds = process_cpu_seconds() - cpu;
  out.spp = spp;
  const double samples = static_cast<double>(s.scene->width) * s.scene->height * spp;
  out.samples_per_second = samples / out.seconds;
  out.samples_per_cpu_second = samples / out.cpu_seconds;
  return out;
}

}  // namespace pt::bench
