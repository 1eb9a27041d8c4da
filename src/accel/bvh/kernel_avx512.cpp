// The same kernel (kernel_wide.h) compiled with AVX-512 F, VL, DQ and BW on top
// of AVX2 and FMA (-ffp-contract=off still): the same 8-lane operations, with
// 32 vector registers (the ray's constants stay in registers across the loop)
// and mask registers for the comparisons. Called only after
// cpu_has_avx512() (bvh_accel.cpp). Measured in docs/bvh.md (session 11).
#include "accel/bvh/kernel_wide.h"

namespace pt::bvh {

KernelTable avx512_kernels() { return KernelTable{"AVX-512VL", intersect, occluded, intersect_counted}; }

}  // namespace pt::bvh
