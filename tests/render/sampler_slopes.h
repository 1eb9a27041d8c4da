// Convergence-rate checks of 2D integrals for the sampler tests
// (test_samplers.cpp, test_sampler_properties.cpp): a least-squares slope of
// log RMSE against log N over independent replicas, the two analytic
// integrands, and the tolerance bands a correct sampler must fall in.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "core/math.h"

namespace pt::test {

// The n points of replica r (a replica is an independent estimate: another pixel, another seed).
using PointSet = std::function<std::vector<Vec2f>(int replica, int n)>;

// Least-squares slope of log(RMSE) against log(N) of the estimate of the
// integral of f over [0,1)^2: RMSE over 256 replicas at N = 16, 64, 256, 1024.
inline double rmse_slope(const PointSet& points, const std::function<double(double, double)>& f, double exact) {
  constexpr int kReplicas = 256;
  std::vector<double> log_n, log_rmse;
  for (int n : {16, 64, 256, 1024}) {
    double sum_sq = 0.0;
    for (int r = 0; r < kReplicas; ++r) {
      double estimate = 0.0;
      for (const Vec2f& p : points(r, n)) estimate += f(p.x, p.y);
      estimate /= n;
      sum_sq += (estimate - exact) * (estimate - exact);
    }
    log_n.push_back(std::log(static_cast<double>(n)));
    log_rmse.push_back(0.5 * std::log(sum_sq / kReplicas));
  }
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < log_n.size(); ++i) mx += log_n[i] / 4, my += log_rmse[i] / 4;
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < log_n.size(); ++i) {
    sxy += (log_n[i] - mx) * (log_rmse[i] - my);
    sxx += (log_n[i] - mx) * (log_n[i] - mx);
  }
  return sxy / sxx;
}

// A Gaussian bump (sigma 0.2, smooth) and a disk indicator (radius 0.4, an edge).
constexpr double kGaussianSigma = 0.2, kDiskRadius = 0.4;
inline double gaussian(double x, double y) {
  return std::exp(-((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)) / (2 * kGaussianSigma * kGaussianSigma));
}
inline double gaussian_integral() {
  const double g1 = kGaussianSigma * std::sqrt(2 * M_PI) * std::erf(0.5 / (kGaussianSigma * std::sqrt(2.0)));
  return g1 * g1;
}
inline double disk(double x, double y) {
  return (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5) < kDiskRadius * kDiskRadius ? 1.0 : 0.0;
}
inline double disk_integral() { return M_PI * kDiskRadius * kDiskRadius; }

// Expected RMSE slopes and tolerances (docs/samplers.md): random N^-0.5;
// jittered N^-1 (smooth), N^-0.75 (edge); Owen-scrambled Sobol' N^-1.5
// sqrt(log N) (smooth: about -1.4 fitted over N = 16..1024), N^-0.75 (edge).
// +-0.15 (+-0.2 for Sobol' smooth) is several times a slope's own noise
// (about 0.03 with 256 replicas) and separates each sampler from the next
// better one; test_sampler_properties.cpp shows broken samplers falling outside.
struct SlopeBand {
  double centre, tolerance;
  bool contains(double slope) const { return std::abs(slope - centre) <= tolerance; }
};
constexpr SlopeBand kRandomBand{-0.5, 0.15};
constexpr SlopeBand kJitteredSmoothBand{-1.0, 0.15};
constexpr SlopeBand kJitteredEdgeBand{-0.75, 0.15};
constexpr SlopeBand kSobolSmoothBand{-1.4, 0.2};
constexpr SlopeBand kSobolEdgeBand{-0.75, 0.15};

}  // namespace pt::test
