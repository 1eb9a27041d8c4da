#include "render/textures/procedural.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace pt {

namespace {

// Ken Perlin's permutation of 0..255 (the reference implementation of "Improving
// Noise", SIGGRAPH 2002), indexed modulo 256.
constexpr uint8_t kPermutation[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,  69,  142,
    8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203,
    117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165,
    71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,
    55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,
    18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250,
    124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189,
    28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114,
    67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};

int perm(int i) { return kPermutation[i & 255]; }

float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
float lerp(float t, float a, float b) { return a + t * (b - a); }

float grad(int hash, float x, float y, float z) {
  const int h = hash & 15;
  const float u = h < 8 ? x : y;
  const float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}

// The lattice cell of x (reduced modulo 256, where the noise repeats, so that
// huge coordinates neither overflow an int nor lose the fraction's sign) and
// the offset in it.
void cell(float x, int& i, float& f) {
  const float fl = std::floor(x);
  f = x - fl;
  i = static_cast<int>(std::fmod(fl, 256.0f));
  if (i < 0) i += 256;
}

RGB blend(RGB a, RGB b, float t) { return a * (1.0f - t) + b * t; }

float smooth_step(float a, float b, float x) {
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The integral from 0 to x of the square wave: a triangle wave of period 2.
float wave_integral(float x) {
  const float m = x - 2.0f * std::floor(0.5f * x);
  return 1.0f - std::fabs(m - 1.0f);
}

}  // namespace

float checker_wave_average(float x, float w) {
  // Below this width the difference of the integrals is mostly rounding: the point value.
  if (!(w > 1e-4f)) return std::fmod(std::floor(x), 2.0f) == 0.0f ? 1.0f : -1.0f;
  return (wave_integral(x + w) - wave_integral(x - w)) / (2.0f * w);
}

RGB evaluate(const CheckerTexture& t, Vec3f c, Vec3f dcdx, Vec3f dcdy) {
  if (!is_finite(c)) return blend(t.color0, t.color1, 0.5f);
  // Half widths of the box around c holding the footprint (one pixel wide).
  const Vec3f w = max(abs(dcdx), abs(dcdy)) * 0.5f;
  float s = checker_wave_average(c.x, w.x) * checker_wave_average(c.y, w.y);
  if (t.three_d) s *= checker_wave_average(c.z, w.z);
  return blend(t.color0, t.color1, 0.5f - 0.5f * s);
}

float perlin_noise(Vec3f p) {
  int xi, yi, zi;
  float x, y, z;
  cell(p.x, xi, x);
  cell(p.y, yi, y);
  cell(p.z, zi, z);
  const float u = fade(x), v = fade(y), w = fade(z);
  const int a = perm(xi) + yi, aa = perm(a) + zi, ab = perm(a + 1) + zi;
  const int b = perm(xi + 1) + yi, ba = perm(b) + zi, bb = perm(b + 1) + zi;
  return lerp(w,
              lerp(v, lerp(u, grad(perm(aa), x, y, z), grad(perm(ba), x - 1, y, z)),
                   lerp(u, grad(perm(ab), x, y - 1, z), grad(perm(bb), x - 1, y - 1, z))),
              lerp(v, lerp(u, grad(perm(aa + 1), x, y, z - 1), grad(perm(ba + 1), x - 1, y, z - 1)),
                   lerp(u, grad(perm(ab + 1), x, y - 1, z - 1), grad(perm(bb + 1), x - 1, y - 1, z - 1))));
}

float fbm(Vec3f p, Vec3f dpdx, Vec3f dpdy, float roughness, int octaves) {
  // Octave i has features of size about 1 / 2^i: keep those wider than the footprint.
  const float len2 = std::max(length_squared(dpdx), length_squared(dpdy));
  const float max_octaves = static_cast<float>(std::max(octaves, 0));
  const float n = len2 > 0.0f ? std::clamp(-1.0f - 0.5f * std::log2(len2), 0.0f, max_octaves) : max_octaves;
  const int whole = static_cast<int>(std::floor(n));
  float sum = 0.0f, lambda = 1.0f, o = 1.0f;
  for (int i = 0; i < whole; ++i) {
    sum += o * perlin_noise(p * lambda);
    lambda *= 1.99f;
    o *= roughness;
  }
  const float partial = n - static_cast<float>(whole);
  if (partial > 0.0f) sum += o * smooth_step(0.3f, 0.7f, partial) * perlin_noise(p * lambda);
  return sum;
}

RGB evaluate(const NoiseTexture& t, Vec3f c, Vec3f dcdx, Vec3f dcdy) {
  if (!is_finite(c)) return blend(t.color0, t.color1, 0.5f);
  const float f = fbm(c, dcdx, dcdy, t.roughness, t.octaves);
  return blend(t.color0, t.color1, std::clamp(0.5f + 0.5f * f, 0.0f, 1.0f));
}

}  // namespace pt
