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

inline void set_ray_frame(RayQuery& q) {
  for (int a = 0; a < 3; ++a) {
    q.rdir[a] = 1.0f / q.dir[a];  // +-inf for +-0: the sign picks the entry plane
    q.near[a] = std::signbit(q.dir[a]) ? 1u : 0u;
  }
  // The ray frame of the watertight triangle test, computed exactly as
  // intersect_triangle() computes it (geometry/triangle.cpp).
  const Vec3f dir(q.dir[0], q.dir[1], q.dir[2]);
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
