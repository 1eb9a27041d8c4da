// The AVX2 + FMA kernel (kernel_wide.h), compiled with -mavx2 -mfma
// -ffp-contract=off and called only after cpu_has_avx2_fma() (bvh_accel.cpp).
#include "accel/bvh/kernel_wide.h"

namespace pt::bvh {

KernelTable avx2_kernels() { return KernelTable{"AVX2", intersect, occluded, intersect_counted}; }

}  // namespace pt::bvh
