// Small fixed-size vector math used everywhere in the renderer.
// Plain structs, free functions, no hidden state.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace pt {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Vec2f {
  float x = 0, y = 0;
  constexpr Vec2f() = default;
  constexpr Vec2f(float x_, float y_) : x(x_), y(y_) {}
  constexpr Vec2f operator+(Vec2f b) const { return {x + b.x, y + b.y}; }
  constexpr Vec2f operator-(Vec2f b) const { return {x - b.x, y - b.y}; }
  constexpr Vec2f operator*(float s) const { return {x * s, y * s}; }
  constexpr bool operator==(const Vec2f&) const = default;
};

struct Vec3f {
  float x = 0, y = 0, z = 0;
  constexpr Vec3f() = default;
  constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3f(float s) : x(s), y(s), z(s) {}

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f operator+(Vec3f b) const { return {x + b.x, y + b.y, z + b.z}; }
  constexpr Vec3f operator-(Vec3f b) const { return {x - b.x, y - b.y, z - b.z}; }
  constexpr Vec3f operator*(Vec3f b) const { return {x * b.x, y * b.y, z * b.z}; }
  constexpr Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3f operator/(float s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3f& operator+=(Vec3f b) { x += b.x; y += b.y; z += b.z; return *this; }
  constexpr Vec3f& operator-=(Vec3f b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
  constexpr Vec3f& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
  constexpr bool operator==(const Vec3f&) const = default;
};

constexpr Vec3f operator*(float s, Vec3f v) { return v * s; }
constexpr float dot(Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3f cross(Vec3f a, Vec3f b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3f v) { return std::sqrt(dot(v, v)); }
constexpr float length_squared(Vec3f v) { return dot(v, v); }
inline Vec3f normalize(Vec3f v) { return v / length(v); }
inline Vec3f abs(Vec3f v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }
inline Vec3f min(Vec3f a, Vec3f b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3f max(Vec3f a, Vec3f b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
inline float max_component(Vec3f v) { return std::max(v.x, std::max(v.y, v.z)); }
inline bool is_finite(Vec3f v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Reflect `v` (pointing away from the surface) about normal `n`.
inline Vec3f reflect(Vec3f v, Vec3f n) { return 2.0f * dot(v, n) * n - v; }

// Builds an orthonormal basis around unit vector n (Duff et al. 2017).
inline void orthonormal_basis(Vec3f n, Vec3f& t, Vec3f& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float bb = n.x * n.y * a;
  t = {1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x};
  b = {bb, sign + n.y * n.y * a, -n.y};
}

struct Bounds3f {
  Vec3f lo{kInfinity, kInfinity, kInfinity};
  Vec3f hi{-kInfinity, -kInfinity, -kInfinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(Vec3f p) { lo = min(lo, p); hi = max(hi, p); }
  void extend(const Bounds3f& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
  Vec3f centre() const { return (lo + hi) * 0.5f; }
  Vec3f extent() const { return hi - lo; }
};

// A ray with its valid parametric interval [tmin, tmax].
struct Ray {
  Vec3f origin;
  Vec3f dir;
  float tmin = 0.0f;
  float tmax = kInfinity;
  Vec3f at(float t) const { return origin + dir * t; }
};

}  // namespace pt
