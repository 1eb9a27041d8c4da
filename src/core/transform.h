// Affine transforms: a 3x4 matrix acting on column vectors (the implicit last
// row is 0 0 0 1) together with its inverse. Built and composed in double
// (Affine), stored in float (Transform) for the renderer. Points, vectors and
// normals (by the inverse transpose), rays and boxes; the error bound of a
// transformed point (pbrt-v4, "Transformations" in "Floating-Point Error"), so
// that a surface point carried to world space keeps a safe ray offset.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace pt {

// A double-precision affine map, for building transforms from a scene file's
// steps. m[r][c]: row r, column c; column 3 is the translation.
struct Affine {
  double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

  static Affine translate(double x, double y, double z) {
    Affine a;
    a.m[0][3] = x;
    a.m[1][3] = y;
    a.m[2][3] = z;
    return a;
  }
  static Affine scale(double x, double y, double z) {
    Affine a;
    a.m[0][0] = x;
    a.m[1][1] = y;
    a.m[2][2] = z;
    return a;
  }
  // Counter-clockwise by `degrees` about `axis` (any non-zero length) looking
  // down the axis towards the origin (right-handed, as pbrt-v4 and Mitsuba 3).
  static Affine rotate(double ax, double ay, double az, double degrees) {
    const double len = std::sqrt(ax * ax + ay * ay + az * az);
    const double x = ax / len, y = ay / len, z = az / len;
    const double rad = degrees * 3.14159265358979323846 / 180.0;
    const double s = std::sin(rad), c = std::cos(rad), t = 1.0 - c;
    Affine a;
    a.m[0][0] = t * x * x + c;
    a.m[0][1] = t * x * y - s * z;
    a.m[0][2] = t * x * z + s * y;
    a.m[1][0] = t * x * y + s * z;
    a.m[1][1] = t * y * y + c;
    a.m[1][2] = t * y * z - s * x;
    a.m[2][0] = t * x * z - s * y;
    a.m[2][1] = t * y * z + s * x;
    a.m[2][2] = t * z * z + c;
    return a;
  }
  // this ∘ b: b applied first.
  Affine operator*(const Affine& b) const {
    Affine r;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) {
        double v = j == 3 ? m[i][3] : 0.0;
        for (int k = 0; k < 3; ++k) v += m[i][k] * b.m[k][j];
        r.m[i][j] = v;
      }
    }
    return r;
  }
  double determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  bool finite() const {
    for (const auto& row : m) {
      for (double v : row) {
        if (!std::isfinite(v)) return false;
      }
    }
    return true;
  }
  // Whether the linear part is invertible in a way float can use: the
  // determinant, relative to the product of the rows' lengths, is not
  // vanishingly small (a matrix with a zero or near-parallel rows is refused).
  bool invertible() const {
    double norms = 1.0;
    for (const auto& row : m) norms *= std::sqrt(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]);
    const double det = determinant();
    return finite() && norms > 0.0 && std::isfinite(det) && std::fabs(det) > 1e-12 * norms;
  }
  // The inverse; only for invertible() maps.
  Affine inverse() const {
    const double d = 1.0 / determinant();
    Affine r;
    r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * d;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * d;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * d;
    r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * d;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * d;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * d;
    r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * d;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * d;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * d;
    for (int i = 0; i < 3; ++i) r.m[i][3] = -(r.m[i][0] * m[0][3] + r.m[i][1] * m[1][3] + r.m[i][2] * m[2][3]);
    return r;
  }
  bool is_identity() const {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) {
        if (m[i][j] != (i == j ? 1.0 : 0.0)) return false;
      }
    }
    return true;
  }
};

// The renderer's transform: object to world (m) and world to object (inv),
// both rounded once from the double-precision map.
struct Transform {
  float m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
  float inv[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
  float det = 1.0f;        // determinant of the linear part (negative: mirrored)
  float scale = 1.0f;      // the uniform scale factor, when is_similarity()
  bool similarity = true;  // rotation (or reflection) times uniform scale, plus translation

  Transform() = default;
  // `a` must be invertible().
  explicit Transform(const Affine& a) {
    const Affine b = a.inverse();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) {
        m[i][j] = static_cast<float>(a.m[i][j]);
        inv[i][j] = static_cast<float>(b.m[i][j]);
      }
    }
    const double d = a.determinant();
    det = static_cast<float>(d);
    // Similar iff the columns are orthogonal with equal lengths (relative 1e-5).
    double g[3][3];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) g[i][j] = a.m[0][i] * a.m[0][j] + a.m[1][i] * a.m[1][j] + a.m[2][i] * a.m[2][j];
    }
    const double s2 = std::cbrt(d * d);
    similarity = true;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (std::fabs(g[i][j] - (i == j ? s2 : 0.0)) > 1e-5 * s2) similarity = false;
      }
    }
    scale = static_cast<float>(std::sqrt(s2));
  }

  bool is_identity() const {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) {
        if (m[i][j] != (i == j ? 1.0f : 0.0f)) return false;
      }
    }
    return true;
  }
  // Whether both matrices and the determinant are finite in float.
  bool finite() const {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) {
        if (!std::isfinite(m[i][j]) || !std::isfinite(inv[i][j])) return false;
      }
    }
    return std::isfinite(det) && det != 0.0f;
  }

  Vec3f point(Vec3f p) const { return apply(m, p, true); }
  Vec3f vector(Vec3f v) const { return apply(m, v, false); }
  Vec3f inverse_point(Vec3f p) const { return apply(inv, p, true); }
  Vec3f inverse_vector(Vec3f v) const { return apply(inv, v, false); }
  // A normal (inverse transpose; not normalised). Keeps the outward side also
  // under a mirroring map.
  Vec3f normal(Vec3f n) const {
    return {inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z, inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
            inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z};
  }
  // The transpose of the linear part times v (world normal back to object space, unnormalised).
  Vec3f transpose_vector(Vec3f v) const {
    return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
            m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
  }
  // The world ray in object space: same t parameter (the direction is not
  // renormalised), same interval.
  Ray to_object(const Ray& r) const { return Ray{inverse_point(r.origin), inverse_vector(r.dir), r.tmin, r.tmax}; }

  // Bounds of the transformed box (its eight corners), widened by the
  // rounding of the transform so that no transformed point falls outside.
  Bounds3f bounds(const Bounds3f& b) const {
    Bounds3f out;
    if (b.empty()) return out;
    for (int c = 0; c < 8; ++c) {
      const Vec3f p((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
      const Vec3f q = point(p);
      const Vec3f e = point_error(p, Vec3f(0.0f));
      out.extend(q - e);
      out.extend(q + e);
    }
    return out;
  }

  // Bound on the absolute error of point(p) for a p known to within p_error
  // (pbrt-v4's (1 + g) |M| p_error + g (|M| |p| + |t|), with g = gamma(5)
  // rather than pbrt's gamma(3): a row is four terms, the first rounded four
  // times, and the bound itself is computed in float; tests/core checks it).
  Vec3f point_error(Vec3f p, Vec3f p_error) const {
    constexpr float g5 = (5.0f * 0x1p-24f) / (1.0f - 5.0f * 0x1p-24f);
    float e[3];
    for (int i = 0; i < 3; ++i) {
      const float ap = std::fabs(m[i][0] * p.x) + std::fabs(m[i][1] * p.y) + std::fabs(m[i][2] * p.z) +
                       std::fabs(m[i][3]);
      const float ae = std::fabs(m[i][0]) * p_error.x + std::fabs(m[i][1]) * p_error.y +
                       std::fabs(m[i][2]) * p_error.z;
      e[i] = (1.0f + g5) * ae + g5 * ap;
    }
    return {e[0], e[1], e[2]};
  }

  // Bound, in world space, on the error of taking world point p to object
  // space (inverse_point): a ray leaving p is transformed back there before
  // it is intersected, so a spawned ray's offset must also cover this
  // (|M| gamma(5) (|M^-1| |p| + |t^-1|)); it dominates far from the origin.
  Vec3f inverse_error(Vec3f p) const {
    constexpr float g5 = (5.0f * 0x1p-24f) / (1.0f - 5.0f * 0x1p-24f);
    float e[3];
    for (int j = 0; j < 3; ++j) {
      e[j] = g5 * (std::fabs(inv[j][0] * p.x) + std::fabs(inv[j][1] * p.y) + std::fabs(inv[j][2] * p.z) +
                   std::fabs(inv[j][3]));
    }
    float w[3];
    for (int i = 0; i < 3; ++i) {
      w[i] = (1.0f + g5) * (std::fabs(m[i][0]) * e[0] + std::fabs(m[i][1]) * e[1] + std::fabs(m[i][2]) * e[2]);
    }
    return {w[0], w[1], w[2]};
  }

 private:
  static Vec3f apply(const float (&a)[3][4], Vec3f p, bool translate) {
    const float w = translate ? 1.0f : 0.0f;
    return {a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3] * w,
            a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3] * w,
            a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3] * w};
  }
};

}  // namespace pt
