// Chi-square goodness-of-fit tests of sampling routines against their
// densities, in the style of pbrt-v4's and Mitsuba 3's test suites.
//
// A sampler is run N times with independent uniform numbers; its outputs are
// binned; the expected count of every bin is N times the integral of the
// claimed density over the bin (adaptive Simpson quadrature). Bins whose
// expected count is below 5 are pooled (smallest first) until they are not;
// a sample in a bin where the density integrates to zero fails at once. The
// statistic sum (O - E)^2 / E is compared with the chi-square distribution of
// (bins - 1) degrees of freedom; the test fails when its p-value is below the
// Sidak-corrected significance 1 - (1 - alpha)^(1/M) for alpha = 1% spread
// over the M chi-square tests of the suite, so that the whole suite has a 1%
// chance of a false alarm.
//
// Directions are binned over the sphere in (cos theta, phi) of a chosen frame
// (equal solid angle per bin); sharp lobes are binned in a frame whose pole is
// perpendicular to the lobe, where the bins are narrowest in theta.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"

namespace pt::test {

// The number of chi-square tests in the suite (tests/core/test_warps.cpp and
// tests/render/test_chi2_*.cpp), for the Sidak correction.
inline constexpr int kChi2TestCount = 79;  // 11 warps, 21 + 26 microfacet BSDF, 16 light, 2 filter, 3 light choice tests
inline double chi2_significance(double alpha = 0.01, int tests = kChi2TestCount) {
  return 1.0 - std::pow(1.0 - alpha, 1.0 / tests);
}

// Regularised upper incomplete gamma Q(a, x) (Numerical Recipes: series for
// x < a + 1, Lentz continued fraction otherwise).
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double gln = std::lgamma(a);
  if (x < a + 1.0) {
    double ap = a, sum = 1.0 / a, del = sum;
    for (int n = 0; n < 10000; ++n) {
      ap += 1.0;
      del *= x / ap;
      sum += del;
      if (std::fabs(del) < std::fabs(sum) * 1e-15) break;
    }
    return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

struct Chi2Result {
  bool passed = false;
  double statistic = 0.0;
  int dof = 0;
  double p_value = 0.0;
  std::string message;  // why it failed, or a summary
};

// Goodness of fit of observed counts to expected counts (same binning).
inline Chi2Result chi2_gof(const std::vector<double>& observed, const std::vector<double>& expected,
                           double significance = chi2_significance(), double min_expected = 5.0) {
  Chi2Result r;
  if (const char* v = std::getenv("PT_CHI2_VERBOSE"); v && v[0] == '2') {
    std::vector<std::pair<double, std::size_t>> worst;
    for (std::size_t i = 0; i < observed.size(); ++i)
      if (expected[i] > 0) worst.push_back({(observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i], i});
    std::sort(worst.rbegin(), worst.rend());
    for (std::size_t k = 0; k < std::min<std::size_t>(8, worst.size()); ++k)
      std::fprintf(stderr, "  bin %zu: observed %g expected %g\n", worst[k].second, observed[worst[k].second],
                   expected[worst[k].second]);
  }
  std::vector<std::size_t> order(observed.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  double pooled_obs = 0.0, pooled_exp = 0.0;
  int bins = 0, pooled_bins = 0;
  for (std::size_t i : order) {
    if (expected[i] <= 0.0) {
      if (observed[i] > 0.0) {
        std::ostringstream os;
        os << observed[i] << " samples in bin " << i << " where the density integrates to " << expected[i];
        r.message = os.str();
        return r;
      }
      continue;
    }
    if (expected[i] < min_expected) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      ++pooled_bins;
      if (pooled_exp >= min_expected) {
        r.statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        ++bins;
        pooled_obs = pooled_exp = 0.0;
      }
      continue;
    }
    r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++bins;
  }
  if (pooled_exp > 0.0) {  // the remainder joins the statistic as one more bin
    r.statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    ++bins;
  }
  r.dof = bins - 1;
  if (r.dof < 1) {
    r.message = "too few bins with enough expected samples";
    return r;
  }
  r.p_value = gamma_q(0.5 * r.dof, 0.5 * r.statistic);
  r.passed = r.p_value >= significance;
  std::ostringstream os;
  os << "chi2 = " << r.statistic << " with " << r.dof << " degrees of freedom (" << pooled_bins
     << " bins pooled), p = " << r.p_value << ", significance " << significance;
  r.message = os.str();
  if (std::getenv("PT_CHI2_VERBOSE")) std::fprintf(stderr, "%s\n", r.message.c_str());
  return r;
}

// Adaptive Simpson quadrature of f over [a, b]. The first kMinSplits levels
// are always split: a coarse estimate can agree with itself while missing a
// feature narrower than its sample spacing (the corner of a triangle inside a bin).
inline constexpr int kMinSplits = 4;

template <class F>
double simpson_step(const F& f, double x0, double x1, double f0, double f1, double fm, double whole, double eps,
                    int level, int depth) {
  const double xm = 0.5 * (x0 + x1);
  const double fl = f(0.5 * (x0 + xm)), fr = f(0.5 * (xm + x1));
  const double left = (xm - x0) / 6.0 * (f0 + 4.0 * fl + fm);
  const double right = (x1 - xm) / 6.0 * (fm + 4.0 * fr + f1);
  const double delta = left + right - whole;
  if (level >= depth || (level >= kMinSplits && std::fabs(delta) <= 15.0 * eps)) return left + right + delta / 15.0;
  return simpson_step(f, x0, xm, f0, fm, fl, left, 0.5 * eps, level + 1, depth) +
         simpson_step(f, xm, x1, fm, f1, fr, right, 0.5 * eps, level + 1, depth);
}

template <class F>
double adaptive_simpson(const F& f, double a, double b, double eps, int depth) {
  const double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
  return simpson_step(f, a, b, fa, fb, fm, (b - a) / 6.0 * (fa + 4.0 * fm + fb), eps, 0, depth);
}

// 2D adaptive Simpson over [x0, x1] x [y0, y1] (nested 1D). The rectangle is
// shrunk by 1e-6 of its size on every side, so that a density that jumps
// exactly at a bin edge (a hemisphere at cos theta = 0) is not sampled on the
// wrong side of the jump; the mass lost is a few parts per million.
template <class F>
double integrate_2d(const F& f, double x0, double x1, double y0, double y1, double eps = 1e-7, int depth = 7) {
  const double ix = 1e-6 * (x1 - x0), iy = 1e-6 * (y1 - y0);
  x0 += ix;
  x1 -= ix;
  y0 += iy;
  y1 -= iy;
  const auto row = [&](double y) { return adaptive_simpson([&](double x) { return f(x, y); }, x0, x1, eps, depth); };
  return (1.0 + 4e-6) * adaptive_simpson(row, y0, y1, eps, depth);
}

// Chi-square test of a direction sampler. `sample(u1, u2, dir)` returns false
// for a failed sample (its mass is missing from the density too); `pdf(dir)`
// is the claimed solid-angle density. Bins: n_theta bins in cos(theta) over
// [-1, 1] and n_phi in phi, in the frame `bins`.
struct DirectionChi2 {
  std::function<bool(float, Vec2f, Vec3f&)> sample;  // (u1, u2, out)
  std::function<float(Vec3f)> pdf;
  Frame bins;
  int n_theta = 32, n_phi = 64;
  int samples = 1000000;
  uint64_t seed = 1;
  int quadrature_depth = 7;  // raise for densities with large jumps inside bins

  Chi2Result run() const {
    const int n = n_theta * n_phi;
    std::vector<double> observed(static_cast<std::size_t>(n), 0.0), expected(static_cast<std::size_t>(n), 0.0);
    Rng rng(seed);
    for (int i = 0; i < samples; ++i) {
      const float u0 = rng.next_float();
      const float u1 = rng.next_float();
      const float u2 = rng.next_float();
      Vec3f d;
      if (!sample(u0, Vec2f(u1, u2), d)) continue;
      const Vec3f l = bins.to_local(normalize(d));
      const int t = std::clamp(static_cast<int>((l.z + 1.0f) * 0.5f * static_cast<float>(n_theta)), 0, n_theta - 1);
      const int p = std::clamp(static_cast<int>(spherical_phi(l) * kInv2Pi * static_cast<float>(n_phi)), 0, n_phi - 1);
      observed[static_cast<std::size_t>(t * n_phi + p)] += 1.0;
    }
    auto density = [&](double cos_theta, double phi) {
      const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
      const Vec3f l(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                    static_cast<float>(cos_theta));
      return static_cast<double>(pdf(bins.from_local(l)));
    };
    // A bin is integrated if it or a neighbour received samples, or if the
    // density is non-zero somewhere on a 5 x 5 probe grid in it; otherwise its
    // expectation is taken as 0 (a bin with samples is never skipped, so a
    // sample where the density vanishes is still caught).
    auto near_samples = [&](int t, int p) {
      for (int dt = -1; dt <= 1; ++dt)
        for (int dp = -1; dp <= 1; ++dp) {
          const int tt = t + dt, pp = (p + dp + n_phi) % n_phi;
          if (tt >= 0 && tt < n_theta && observed[static_cast<std::size_t>(tt * n_phi + pp)] > 0.0) return true;
        }
      return false;
    };
    for (int t = 0; t < n_theta; ++t) {
      for (int p = 0; p < n_phi; ++p) {
        const double c0 = -1.0 + 2.0 * t / n_theta, c1 = -1.0 + 2.0 * (t + 1) / n_theta;
        const double p0 = 2.0 * M_PI * p / n_phi, p1 = 2.0 * M_PI * (p + 1) / n_phi;
        bool needed = near_samples(t, p);
        for (int i = 0; i < 25 && !needed; ++i)
          needed = density(c0 + (c1 - c0) * (0.1 + 0.2 * (i % 5)), p0 + (p1 - p0) * (0.1 + 0.2 * (i / 5))) > 0.0;
        if (!needed) continue;
        expected[static_cast<std::size_t>(t * n_phi + p)] =
            samples * integrate_2d(density, c0, c1, p0, p1, 1e-7, quadrature_depth);
      }
    }
    return chi2_gof(observed, expected);
  }
};

// Chi-square test of a sampler of points in the rectangle [x0, x1] x [y0, y1]
// with area density pdf(p), on an nx x ny grid.
struct PlaneChi2 {
  std::function<bool(Vec2f, Vec2f&)> sample;
  std::function<float(Vec2f)> pdf;
  float x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  int nx = 32, ny = 32;
  int samples = 1000000;
  uint64_t seed = 1;

  Chi2Result run() const {
    std::vector<double> observed(static_cast<std::size_t>(nx * ny), 0.0), expected(observed.size(), 0.0);
    Rng rng(seed);
    for (int i = 0; i < samples; ++i) {
      const float u = rng.next_float();
      const float v = rng.next_float();
      Vec2f q;
      if (!sample(Vec2f(u, v), q)) continue;
      const int ix = static_cast<int>(std::floor((q.x - x0) / (x1 - x0) * static_cast<float>(nx)));
      const int iy = static_cast<int>(std::floor((q.y - y0) / (y1 - y0) * static_cast<float>(ny)));
      if (ix < 0 || ix >= nx || iy < 0 || iy >= ny) {
        Chi2Result r;
        r.message = "a sample left the domain";
        return r;
      }
      observed[static_cast<std::size_t>(iy * nx + ix)] += 1.0;
    }
    auto density = [&](double x, double y) {
      return static_cast<double>(pdf(Vec2f(static_cast<float>(x), static_cast<float>(y))));
    };
    for (int iy = 0; iy < ny; ++iy) {
      for (int ix = 0; ix < nx; ++ix) {
        const double a0 = x0 + (x1 - x0) * ix / nx, a1 = x0 + (x1 - x0) * (ix + 1) / nx;
        const double b0 = y0 + (y1 - y0) * iy / ny, b1 = y0 + (y1 - y0) * (iy + 1) / ny;
        expected[static_cast<std::size_t>(iy * nx + ix)] = samples * integrate_2d(density, a0, a1, b0, b1, 1e-7, 6);
      }
    }
    return chi2_gof(observed, expected);
  }
};

// A frame whose pole (z) is perpendicular to `axis`, so that directions near
// `axis` fall on the equator, where the (cos theta) bins are narrowest.
inline Frame frame_across(Vec3f axis) {
  const Frame f = Frame::from_normal(normalize(axis));
  Frame out;
  out.n = f.s;
  out.s = f.t;
  out.t = f.n;
  return out;
}

}  // namespace pt::test
