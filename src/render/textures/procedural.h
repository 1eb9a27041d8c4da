// Procedural textures (docs/textures.md): a checkerboard and fBm noise, each
// a blend of two colours, evaluated at texture-space coordinates `c` (2D
// textures read c.x and c.y; c.z is 0 under the uv mapping) with the
// footprint (dcdx, dcdy) of one pixel, which each filters in closed form or
// by dropping detail finer than the footprint, so that they do not alias
// where an image texture would not. Zero derivatives: a point evaluation.
#pragma once

#include "core/color.h"
#include "core/math.h"

namespace pt {

// color0 where floor(x) + floor(y) (+ floor(z) in 3D) is even, color1 where it
// is odd: squares (cubes) of side 1 in texture space. Filtered exactly over
// the axis-aligned box around c that holds the footprint (the checker is a
// product of square waves, so its box average is the product of their
// averages).
struct CheckerTexture {
  RGB color0{0.0f};
  RGB color1{1.0f};
  bool three_d = false;
};

// fBm of Perlin's improved gradient noise (pbrt-v4's FBm): `octaves` octaves,
// each of twice the frequency (x 1.99) and `roughness` times the amplitude of
// the one before; octaves finer than the footprint are left out (the last
// one faded in). The sum, about -1 to 1, blends color0 (at -1 and below) to
// color1 (at 1 and above) through its midpoint at 0.
struct NoiseTexture {
  RGB color0{0.0f};
  RGB color1{1.0f};
  int octaves = 6;
  float roughness = 0.5f;
};

RGB evaluate(const CheckerTexture& t, Vec3f c, Vec3f dcdx, Vec3f dcdy);
RGB evaluate(const NoiseTexture& t, Vec3f c, Vec3f dcdx, Vec3f dcdy);

// The pieces, for tests. The box average over [x - w, x + w] of the square
// wave that is +1 where floor(x) is even and -1 where it is odd (w = 0: its value).
float checker_wave_average(float x, float w);
// Perlin's improved noise (2002), 0 at integer lattice points, within about [-1, 1].
float perlin_noise(Vec3f p);
// pbrt-v4's FBm: `octaves` octaves cut where the footprint is wider than an octave's features.
float fbm(Vec3f p, Vec3f dpdx, Vec3f dpdy, float roughness, int octaves);

}  // namespace pt
