// The traversal kernels, one table per instruction set. Like layout.h this
// header is plain declarations only (see there why).
#pragma once

#include "accel/bvh/layout.h"

namespace pt::bvh {

struct KernelTable {
  const char* isa;  // "SSE2", "AVX2", "AVX-512VL"
  // Nearest hit in (q.tmin, q.tmax); fills `hit` and lowers q.tmax.
  bool (*intersect)(const SceneData& scene, RayQuery& q, HitRecord& hit);
  // Any hit in (q.tmin, q.tmax); returns at the first one found.
  bool (*occluded)(const SceneData& scene, RayQuery& q);
  // As intersect, adding the nodes visited and primitives tested to `counters`.
  bool (*intersect_counted)(const SceneData& scene, RayQuery& q, HitRecord& hit, Counters& counters);
};

// Baseline x86-64 (SSE2): 8-wide nodes tested as two 4-wide halves, triangles
// through the reference routine one by one.
KernelTable sse2_kernels();
// AVX2 + FMA: 8-wide node test, and an 8-wide (two blocks) watertight triangle filter that
// computes exactly what the reference routine computes (same operations, same
// rounding), which then confirms each candidate. Call only where the CPU has
// AVX2 and FMA (cpu_has_avx2_fma()).
KernelTable avx2_kernels();
// The AVX2 kernel's code compiled for AVX-512 F/VL/DQ/BW (8 lanes still; 32
// registers, mask compares). Call only where cpu_has_avx512().
KernelTable avx512_kernels();

bool cpu_has_avx2_fma();
bool cpu_has_avx512();  // AVX2, FMA and AVX-512 F, VL, DQ, BW (usable: the OS saves their state)

// gamma(n) = n u / (1 - n u), u = 2^-24: the constants of the triangle test's
// bound on the error of t, as fp::gamma(n) computes them (leaf_tests.cpp
// checks that they are equal).
inline constexpr float kGamma2 = (2.0f * 0x1p-24f) / (1.0f - 2.0f * 0x1p-24f);
inline constexpr float kGamma3 = (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);
inline constexpr float kGamma5 = (5.0f * 0x1p-24f) / (1.0f - 5.0f * 0x1p-24f);

}  // namespace pt::bvh
