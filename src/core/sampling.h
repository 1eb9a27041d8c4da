// Sampling routines ("warps") that map uniform numbers in [0,1)^n to points
// and directions with a known density, the densities themselves, the power
// heuristic, a local shading frame, and piecewise-constant 1D/2D distributions.
//
// Every sample_* function has a matching *_pdf, and tests/core/test_warps.cpp
// checks each pair with a chi-square goodness-of-fit test. Directions are in a
// local frame whose z axis is the normal (or the cone axis); densities of
// directions are per unit solid angle, densities of points per unit area.
#pragma once

#include <cstddef>
#include <vector>

#include "core/math.h"

namespace pt {

inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
// The largest float below 1: where a uniform number must stay inside [0, 1).
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// ---------------------------------------------------------------- local frame
// An orthonormal frame (s, t, n); to_local/from_local change coordinates.
struct Frame {
  Vec3f s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};

  // A frame around the unit vector n (Duff et al. 2017; continuous except at n.z = -1).
  static Frame from_normal(Vec3f n_) {
    Frame f;
    f.n = n_;
    orthonormal_basis(n_, f.s, f.t);
    return f;
  }
  Vec3f to_local(Vec3f v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3f from_local(Vec3f v) const { return s * v.x + t * v.y + n * v.z; }
};

// ---------------------------------------------------------------- warps
// Shirley-Chiu concentric map from [0,1)^2 onto the unit disk (area preserving).
Vec2f sample_uniform_disk_concentric(Vec2f u);
inline float uniform_disk_pdf() { return kInvPi; }

// Uniform over the hemisphere z >= 0.
Vec3f sample_uniform_hemisphere(Vec2f u);
inline float uniform_hemisphere_pdf() { return kInv2Pi; }

// Cosine-weighted over the hemisphere z >= 0 (Malley's method on the concentric disk).
Vec3f sample_cosine_hemisphere(Vec2f u);
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }

// Uniform over the unit sphere.
Vec3f sample_uniform_sphere(Vec2f u);
inline float uniform_sphere_pdf() { return kInv4Pi; }

// Uniform over the cone of directions within angle theta_max of +z, given
// 1 - cos(theta_max) in (0, 2]. Passing 1 - cos rather than cos keeps narrow
// cones accurate (compute it as sin^2 / (1 + cos), not by subtraction).
Vec3f sample_uniform_cone(Vec2f u, float one_minus_cos_max);
inline float uniform_cone_pdf(float one_minus_cos_max) { return 1.0f / (2.0f * kPi * one_minus_cos_max); }

// Uniform over a triangle: barycentrics (b0, b1, b2) of its corners
// (Heitz 2019, "A Low-Distortion Map Between Triangle and Square").
// The density is 1 / area of the triangle.
Vec3f sample_uniform_triangle(Vec2f u);

// A rectangle as seen from a point p, ready to be sampled uniformly by solid
// angle (Urena, Fajardo, King 2013, "An Area-Preserving Parametrization for
// Spherical Rectangles"): corner c, perpendicular edges ex and ey. In the
// rectangle's frame (x, y along the edges, z towards p's side so that the
// plane is at z0 < 0) it spans [x0, x1] x [y0, y1].
struct SphericalRectangle {
  Vec3f o, x, y, z;             // p and the frame
  float x0 = 0, x1 = 0, y0 = 0, y1 = 0, z0 = 0;
  float b0 = 0, b1 = 0, k = 0;  // the parametrization's constants
  float solid_angle = 0;        // the density of a sample is 1 / solid_angle
};
// False when p lies in the rectangle's plane (it subtends no solid angle).
bool make_spherical_rectangle(Vec3f p, Vec3f c, Vec3f ex, Vec3f ey, SphericalRectangle& out);
// The point of the rectangle whose direction from p is sample u.
Vec3f sample_spherical_rectangle(const SphericalRectangle& r, Vec2f u);

// Veach's power heuristic (beta = 2) for one sample of each of two strategies:
// the weight of a sample of strategy f when g could have produced it too.
inline float power_heuristic(float f_pdf, float g_pdf) {
  const float f = f_pdf * f_pdf, g = g_pdf * g_pdf;
  if (f == kInfinity) return 1.0f;  // a delta distribution wins outright
  return f + g > 0.0f ? f / (f + g) : 0.0f;
}

// Veach's balance heuristic for one sample of each of two strategies: the
// weight of a sample of strategy f, f / (f + g); the same guards as above.
inline float balance_heuristic(float f_pdf, float g_pdf) {
  if (f_pdf == kInfinity) return 1.0f;
  return f_pdf + g_pdf > 0.0f ? f_pdf / (f_pdf + g_pdf) : 0.0f;
}

// Azimuth of a direction in a local frame: phi in [0, 2 pi) from +x towards +y.
float spherical_phi(Vec3f v);

// ---------------------------------------------------------------- distributions
// A piecewise-constant density on [0, 1) with n equal cells whose heights are
// proportional to the given non-negative function values (pbrt's
// PiecewiseConstant1D). The CDF is accumulated in double. If every value is
// zero the density is uniform (and integral() is 0).
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(const std::vector<float>& f);

  std::size_t size() const { return func_.size(); }
  // The integral of the function over [0, 1) (sum of values / n).
  float integral() const { return integral_; }

  // A point in [0, 1) with density pdf(x) = f(cell) / integral; `cell` is its cell.
  float sample_continuous(float u, float* pdf, std::size_t* cell = nullptr) const;
  // A cell index with probability f(cell) / sum f.
  std::size_t sample_discrete(float u, float* pmf = nullptr) const;
  // Probability of cell i under sample_discrete.
  float pmf(std::size_t i) const;
  // Density at x in [0, 1) under sample_continuous.
  float pdf(float x) const;

 private:
  std::size_t find_cell(float u) const;

  std::vector<float> func_;
  std::vector<float> cdf_;  // size n + 1, cdf_[0] = 0, cdf_[n] = 1
  float integral_ = 0.0f;
};

// A piecewise-constant density on [0, 1)^2 over an nu x nv grid (row-major,
// f[v * nu + u]): the marginal in v, then the conditional in u.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(const std::vector<float>& f, int nu, int nv);

  // A point in [0, 1)^2 with density pdf(p).
  Vec2f sample(Vec2f u, float* pdf) const;
  float pdf(Vec2f p) const;
  float integral() const { return marginal_.integral(); }

 private:
  std::vector<Distribution1D> conditional_;
  Distribution1D marginal_;
  int nv_ = 0;
};

}  // namespace pt
