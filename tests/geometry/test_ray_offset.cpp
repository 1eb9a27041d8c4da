// offset_ray_origin() is written with selects instead of branches (its signs
// are unpredictable); this pins it, bit for bit, to the plain definition:
// offset along the geometric normal to the side the ray leaves on, then one
// ulp further away from the surface in every component that moved.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "geometry/float_util.h"
#include "geometry/shapes.h"

namespace pt {
namespace {

Vec3f reference_offset(Vec3f p, Vec3f p_error, Vec3f ng, Vec3f dir) {
  const float d = dot(abs(ng), p_error);
  Vec3f offset = ng * d;
  if (dot(dir, ng) < 0.0f) offset = -offset;
  Vec3f po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.0f) {
      po[i] = fp::next_float_up(po[i]);
    } else if (offset[i] < 0.0f) {
      po[i] = fp::next_float_down(po[i]);
    }
  }
  return po;
}

// Equal bits, or both NaN (a NaN position stays NaN; its payload is not kept).
void expect_same_bits(Vec3f a, Vec3f b) {
  for (int i = 0; i < 3; ++i) {
    if (std::isnan(a[i]) && std::isnan(b[i])) continue;
    EXPECT_EQ(std::bit_cast<uint32_t>(a[i]), std::bit_cast<uint32_t>(b[i])) << "component " << i << ": " << a[i]
                                                                             << " vs " << b[i];
  }
}

TEST(RayOffset, BitIdenticalToTheDefinitionOnSpecialValues) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float denorm = std::numeric_limits<float>::denorm_min();
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, denorm, -denorm, 1e-30f, -1e-30f, 3e38f, -3e38f, inf, -inf, nan};
  const Vec3f normals[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, {0.6f, -0.8f, 0}, {0, 0, 0}};
  const Vec3f errors[] = {{0, 0, 0}, {1e-6f, 1e-6f, 1e-6f}, {0, 0, denorm}};
  const Vec3f dirs[] = {{0, 0, 1}, {0, 0, -1}, {1, 1, 1}, {-1, 0.5f, 0}, {0, 0, 0}};
  int cases = 0;
  for (float x : specials)
    for (float y : {0.0f, -0.0f, 2.5f})
      for (float z : specials)
        for (const Vec3f& n : normals)
          for (const Vec3f& e : errors)
            for (const Vec3f& d : dirs) {
              const Vec3f p(x, y, z);
              expect_same_bits(offset_ray_origin(p, e, n, d), reference_offset(p, e, n, d));
              ++cases;
            }
  EXPECT_GT(cases, 10000);
}

TEST(RayOffset, BitIdenticalToTheDefinitionOnRandomSurfaces) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-20.0f, 20.0f);
  for (int i = 0; i < 200000; ++i) {
    const float scale = std::exp2(exponent(rng));
    const Vec3f p(unit(rng) * scale, unit(rng) * scale, unit(rng) * scale);
    const Vec3f e = abs(p) * fp::gamma(7);
    const Vec3f n = normalize(Vec3f(unit(rng), unit(rng), unit(rng)));
    const Vec3f d(unit(rng), unit(rng), unit(rng));
    expect_same_bits(offset_ray_origin(p, e, n, d), reference_offset(p, e, n, d));
    if (HasFailure()) return;
  }
}

}  // namespace
}  // namespace pt
