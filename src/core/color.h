// Linear RGB colour. Scene-referred values; no gamma anywhere in here.
#pragma once

#include <algorithm>
#include <cmath>

namespace pt {

struct RGB {
  float r = 0, g = 0, b = 0;
  constexpr RGB() = default;
  constexpr RGB(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
  constexpr explicit RGB(float s) : r(s), g(s), b(s) {}

  constexpr RGB operator+(RGB o) const { return {r + o.r, g + o.g, b + o.b}; }
  constexpr RGB operator-(RGB o) const { return {r - o.r, g - o.g, b - o.b}; }
  constexpr RGB operator*(RGB o) const { return {r * o.r, g * o.g, b * o.b}; }
  constexpr RGB operator*(float s) const { return {r * s, g * s, b * s}; }
  constexpr RGB operator/(float s) const { return {r / s, g / s, b / s}; }
  constexpr RGB& operator+=(RGB o) { r += o.r; g += o.g; b += o.b; return *this; }
  constexpr RGB& operator*=(RGB o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
  constexpr RGB& operator*=(float s) { r *= s; g *= s; b *= s; return *this; }
  constexpr bool operator==(const RGB&) const = default;

  constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
  float max_component() const { return std::max(r, std::max(g, b)); }
  // Rec.709 luminance.
  constexpr float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
  bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr RGB operator*(float s, RGB c) { return c * s; }

}  // namespace pt
