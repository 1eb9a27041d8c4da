#include "core/sampling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace pt {

namespace {

// cos and sin of t in [-pi/4, pi/4] by their Taylor polynomials to degree 10
// and 9: the truncation error is below 2e-9, under half a float ulp of the
// results, at a fraction of the cost of a general sincos (the concentric map's
// angles never leave this range).
Vec2f cos_sin_quarter(float t) {
  const float t2 = t * t;
  const float c = 1.0f + t2 * (-1.0f / 2 + t2 * (1.0f / 24 + t2 * (-1.0f / 720 + t2 * (1.0f / 40320 + t2 * (-1.0f / 3628800)))));
  const float s = t * (1.0f + t2 * (-1.0f / 6 + t2 * (1.0f / 120 + t2 * (-1.0f / 5040 + t2 * (1.0f / 362880)))));
  return {c, s};
}

// All ones if `c`, else zero; and a select by such a mask with bit operations,
// which compilers keep as they are (a `c ? a : b` on floats becomes a branch).
uint32_t mask_if(bool c) { return 0u - static_cast<uint32_t>(c); }
float select(uint32_t mask, float a, float b) {
  return std::bit_cast<float>((std::bit_cast<uint32_t>(a) & mask) | (std::bit_cast<uint32_t>(b) & ~mask));
}

}  // namespace

Vec2f sample_uniform_disk_concentric(Vec2f u) {
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  // Written without branches (selects only): which wedge a sample falls in is
  // a coin toss, and a mispredicted branch cost more than the whole map.
  // |a| > |b|: r = a, phi = pi/4 b/a. Otherwise r = b, phi = pi/2 - t with
  // t = pi/4 a/b, so cos phi = sin t and sin phi = cos t. a = b = 0 gives r = 0
  // and the centre.
  const uint32_t wide = mask_if(std::fabs(a) > std::fabs(b));
  const float r = select(wide, a, b);
  const float q = select(wide, b, a);
  const float ratio = select(mask_if(r != 0.0f), q / r, 0.0f);
  const Vec2f cs = cos_sin_quarter(0.25f * kPi * ratio);
  return {r * select(wide, cs.x, cs.y), r * select(wide, cs.y, cs.x)};
}

bool make_spherical_rectangle(Vec3f p, Vec3f c, Vec3f ex, Vec3f ey, SphericalRectangle& r) {
  const float lx = length(ex), ly = length(ey);
  if (!(lx > 0.0f) || !(ly > 0.0f)) return false;
  r.o = p;
  r.x = ex / lx;
  r.y = ey / ly;
  r.z = cross(r.x, r.y);
  const Vec3f d = c - p;
  r.x0 = dot(d, r.x);
  r.y0 = dot(d, r.y);
  r.z0 = dot(d, r.z);
  if (r.z0 > 0.0f) {  // face the frame towards p
    r.z0 = -r.z0;
    r.z = -r.z;
  }
  if (!(r.z0 < 0.0f)) return false;
  r.x1 = r.x0 + lx;
  r.y1 = r.y0 + ly;
  // The normals of the planes through p and each edge, and the rectangle's
  // internal angles on the sphere between consecutive ones.
  const float z0 = r.z0, z2 = z0 * z0;
  const Vec3f n0 = Vec3f(0.0f, z0, -r.y0) / std::sqrt(z2 + r.y0 * r.y0);
  const Vec3f n1 = Vec3f(-z0, 0.0f, r.x1) / std::sqrt(z2 + r.x1 * r.x1);
  const Vec3f n2 = Vec3f(0.0f, -z0, r.y1) / std::sqrt(z2 + r.y1 * r.y1);
  const Vec3f n3 = Vec3f(z0, 0.0f, -r.x0) / std::sqrt(z2 + r.x0 * r.x0);
  auto angle = [](Vec3f a, Vec3f b) { return std::acos(std::clamp(-dot(a, b), -1.0f, 1.0f)); };
  const float g0 = angle(n0, n1), g1 = angle(n1, n2), g2 = angle(n2, n3), g3 = angle(n3, n0);
  r.b0 = n0.z;
  r.b1 = n2.z;
  r.k = 2.0f * kPi - g2 - g3;
  r.solid_angle = g0 + g1 - r.k;
  return r.solid_angle > 0.0f && std::isfinite(r.solid_angle);
}

Vec3f sample_spherical_rectangle(const SphericalRectangle& r, Vec2f u) {
  // x: the spherical area swept from the edge at x0 is u.x times the whole.
  const float au = u.x * r.solid_angle + r.k;
  const float fu = (std::cos(au) * r.b0 - r.b1) / std::sin(au);
  float cu = std::copysign(1.0f, fu) / std::sqrt(fu * fu + r.b0 * r.b0);
  cu = std::clamp(cu, -1.0f, 1.0f);
  float xu = -(cu * r.z0) / std::sqrt(std::max(0.0f, 1.0f - cu * cu));
  xu = std::clamp(xu, r.x0, r.x1);
  // y: uniform in the height of the projection onto the unit sphere along x = xu.
  const float dd = std::sqrt(xu * xu + r.z0 * r.z0);
  const float h0 = r.y0 / std::sqrt(dd * dd + r.y0 * r.y0);
  const float h1 = r.y1 / std::sqrt(dd * dd + r.y1 * r.y1);
  const float hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
  const float yv = hv2 < 1.0f - 1e-6f ? std::clamp(hv * dd / std::sqrt(1.0f - hv2), r.y0, r.y1) : r.y1;
  return r.o + r.x * xu + r.y * yv + r.z * r.z0;
}

Vec3f sample_uniform_hemisphere(Vec2f u) {
  const float z = u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3f sample_cosine_hemisphere(Vec2f u) {
  const Vec2f d = sample_uniform_disk_concentric(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

Vec3f sample_uniform_sphere(Vec2f u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3f sample_uniform_cone(Vec2f u, float one_minus_cos_max) {
  // 1 - cos(theta) is uniform in [0, 1 - cos_max); sin^2 = (1 - cos)(1 + cos)
  // stays accurate for tiny angles.
  const float omc = u.x * one_minus_cos_max;
  const float cos_theta = 1.0f - omc;
  const float sin_theta = std::sqrt(std::max(0.0f, omc * (2.0f - omc)));
  const float phi = 2.0f * kPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

Vec3f sample_uniform_triangle(Vec2f u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = 0.5f * u.x;
    b1 = u.y - b0;
  } else {
    b1 = 0.5f * u.y;
    b0 = u.x - b1;
  }
  return {b0, b1, 1.0f - b0 - b1};
}

float spherical_phi(Vec3f v) {
  const float p = std::atan2(v.y, v.x);
  return p < 0.0f ? p + 2.0f * kPi : p;
}

// ---------------------------------------------------------------- Distribution1D
Distribution1D::Distribution1D(const std::vector<float>& f) : func_(f), cdf_(f.size() + 1) {
  const std::size_t n = func_.size();
  for (float& v : func_) v = (v > 0.0f && std::isfinite(v)) ? v : 0.0f;
  std::vector<double> cdf(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + static_cast<double>(func_[i]) / static_cast<double>(n);
  const double total = n > 0 ? cdf[n] : 0.0;
  integral_ = static_cast<float>(total);
  for (std::size_t i = 0; i <= n; ++i) {
    const double c = total > 0.0 ? cdf[i] / total : static_cast<double>(i) / static_cast<double>(std::max<std::size_t>(n, 1));
    cdf_[i] = static_cast<float>(c);
  }
  if (n > 0) cdf_[n] = 1.0f;
}

std::size_t Distribution1D::find_cell(float u) const {
  // The last i in [0, n) with cdf_[i] <= u: a cell of non-zero width containing u.
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end() - 1, u);
  const std::size_t i = static_cast<std::size_t>(it - cdf_.begin());
  return i == 0 ? 0 : std::min(i - 1, func_.size() - 1);
}

float Distribution1D::sample_continuous(float u, float* pdf, std::size_t* cell) const {
  const std::size_t n = func_.size();
  const std::size_t o = find_cell(u);
  float du = u - cdf_[o];
  const float width = cdf_[o + 1] - cdf_[o];
  if (width > 0.0f) du /= width;
  if (pdf) *pdf = integral_ > 0.0f ? func_[o] / integral_ : 1.0f;
  if (cell) *cell = o;
  const float x = (static_cast<float>(o) + std::clamp(du, 0.0f, 1.0f)) / static_cast<float>(n);
  return std::min(x, kOneMinusEpsilon);
}

std::size_t Distribution1D::sample_discrete(float u, float* pmf_out) const {
  const std::size_t o = find_cell(u);
  if (pmf_out) *pmf_out = pmf(o);
  return o;
}

float Distribution1D::pmf(std::size_t i) const {
  if (i >= func_.size()) return 0.0f;
  const float n = static_cast<float>(func_.size());
  return integral_ > 0.0f ? func_[i] / (integral_ * n) : 1.0f / n;
}

float Distribution1D::pdf(float x) const {
  if (!(x >= 0.0f && x < 1.0f) || func_.empty()) return 0.0f;
  const std::size_t i = std::min(static_cast<std::size_t>(x * static_cast<float>(func_.size())), func_.size() - 1);
  return integral_ > 0.0f ? func_[i] / integral_ : 1.0f;
}

// ---------------------------------------------------------------- Distribution2D
Distribution2D::Distribution2D(const std::vector<float>& f, int nu, int nv) : nv_(nv) {
  conditional_.reserve(static_cast<std::size_t>(nv));
  std::vector<float> row(static_cast<std::size_t>(nu));
  std::vector<float> marginal(static_cast<std::size_t>(nv));
  for (int v = 0; v < nv; ++v) {
    std::copy_n(f.begin() + static_cast<std::ptrdiff_t>(v) * nu, nu, row.begin());
    conditional_.emplace_back(row);
    marginal[static_cast<std::size_t>(v)] = conditional_.back().integral();
  }
  marginal_ = Distribution1D(marginal);
}

Vec2f Distribution2D::sample(Vec2f u, float* pdf_out) const {
  float pdf_v = 0.0f, pdf_u = 0.0f;
  std::size_t row = 0;
  const float y = marginal_.sample_continuous(u.y, &pdf_v, &row);
  const float x = conditional_[row].sample_continuous(u.x, &pdf_u);
  if (pdf_out) *pdf_out = pdf_u * pdf_v;
  return {x, y};
}

float Distribution2D::pdf(Vec2f p) const {
  if (!(p.y >= 0.0f && p.y < 1.0f)) return 0.0f;
  const std::size_t row = std::min(static_cast<std::size_t>(p.y * static_cast<float>(nv_)),
                                   static_cast<std::size_t>(nv_ - 1));
  return conditional_[row].pdf(p.x) * marginal_.pdf(p.y);
}

}  // namespace pt
