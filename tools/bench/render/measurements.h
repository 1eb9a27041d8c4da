// The three measurements of bench_render (docs/performance.md, "Path tracing"):
//  - time to error: progressive passes into one film until the RMSE and the
//    relative MSE against a reference drop below their targets;
//  - throughput: samples per second of one render;
//  - profile: the share of render time spent in ray traversal, by recording
//    every ray a render casts and replaying them through the accelerator alone.
#pragma once

#include <string>
#include <vector>

#include "bench_common.h"

namespace pt::bench {

struct ErrorPoint {
  int spp = 0;
  double seconds = 0;  // render time so far (error evaluation excluded)
  double rmse = 0, relmse = 0;
};

struct TimeToError {
  double seconds_to_rmse = -1, seconds_to_relmse = -1;  // -1: not reached within the limit
  int spp_to_rmse = 0, spp_to_relmse = 0;
  std::vector<ErrorPoint> trace;
  ImageError final_error;
};

TimeToError time_to_error(const LoadedScene& s, const Image& reference, WorkerPool& pool, int pass_spp,
                          double target_rmse, double target_relmse, double max_seconds, uint64_t seed);

// Renders `spp` samples in progressive passes of `pass_spp` and compares the
// result with the reference; writes the image to `output` if not empty and
// hands it back in `result` if not null.
ImageError converge(const LoadedScene& s, const Image& reference, WorkerPool& pool, int spp, int pass_spp,
                    uint64_t seed, const std::string& output, double* seconds, Image* result = nullptr);

struct Throughput {
  int spp = 0;
  double seconds = 0;
  double samples_per_second = 0;  // camera samples (paths) per second
  double cpu_seconds = 0;         // CPU time of the process (every thread) during the render
  double samples_per_cpu_second = 0;
};

Throughput throughput(const LoadedScene& s, WorkerPool& pool, int spp, uint64_t seed);

struct Profile {
  double render_seconds = 0;     // the render, without recording
  double traversal_seconds = 0;  // the same rays replayed through the accelerator alone
  std::size_t rays = 0, shadow_rays = 0;
  double traversal_share() const { return render_seconds > 0 ? traversal_seconds / render_seconds : 0; }
};

// Renders `spp` samples with the scene's accelerator wrapped in a recorder;
// `s.scene` keeps its accelerator afterwards.
Profile profile(LoadedScene& s, WorkerPool& pool, int spp, uint64_t seed);

}  // namespace pt::bench
