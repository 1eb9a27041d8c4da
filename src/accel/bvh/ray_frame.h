// The derived members of a prepared ray (RayQuery: reciprocal direction, entry
// planes, the watertight triangle test's frame), for the baseline-ISA files
// that prepare rays (bvh_accel.cpp: world rays; leaf_tests.cpp: rays taken to
// an instance's object space). Inline, so preparing a world ray costs no call;
// never included by the kernels (see layout.h).
#pragma once

#include <cmath>

#include "accel/bvh/layout.h"
#include "geometry/float_util.h"

namespace pt::bvh {

// From `dir` (== q.dir), read from the caller's Vec3f rather than back from
// q: written this way the world ray's preparation costs what it did before
// instancing (measured: reading q.dir back cost the bvh backend ~5%).
inline void set_ray_frame(Vec3f dir, RayQuery& q) {
  for (int a = 0; a < 3; ++a) {
    q.rdir[a] = 1.0f / dir[a];  // +-inf for +-0: the sign picks the entry plane
    q.near[a] = std::signbit(dir[a]) ? 1u : 0u;
  }
  // The ray frame of the watertight triangle test, computed exactly as
  // intersect_triangle() computes it (geometry/triangle.cpp).
  const int kz = fp::max_dimension(abs(dir));
  const int kx = kz == 2 ? 0 : kz + 1;
  const int ky = kx == 2 ? 0 : kx + 1;
  const Vec3f d = fp::permute(dir, kx, ky, kz);
  q.kx = static_cast<uint32_t>(kx);
  q.ky = static_cast<uint32_t>(ky);
  q.kz = static_cast<uint32_t>(kz);
  q.sz = 1.0f / d.z;
  q.sx = -d.x * q.sz;
  q.sy = -d.y * q.sz;
}

}  // namespace pt::bvh
