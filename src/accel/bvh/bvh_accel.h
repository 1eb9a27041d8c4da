// Our own BVH behind build_accelerator(AccelKind::Bvh, ...): two levels (one
// 8-wide binned-SAH BVH per triangle mesh and one over all analytic shapes,
// and a top level over those), traversed by an AVX2 or a baseline SSE2 kernel
// chosen at run time. Hits are the records the Embree backend returns, found
// by the same src/geometry routines. Design and measurements: docs/bvh.md.
#pragma once

#include <memory>
#include <string>

#include "accel/accelerator.h"
#include "accel/cutout.h"
#include "accel/bvh/blas.h"
#include "accel/bvh/build.h"

namespace pt::bvh {

enum class Isa { Auto, Sse2, Avx2, Avx512 };

struct Options {
  BuildSettings build;
  // Auto: AVX-512 where the CPU has it (kernels.h), else AVX2 where it has AVX2 and FMA, else SSE2.
  Isa isa = Isa::Auto;
  const CutoutTest* cutouts = nullptr;  // the scene's alpha cutouts (accel/cutout.h); must outlive the accelerator
};

// Statistics of the whole structure, for the benchmark and docs/bvh.md.
struct SceneTreeStats {
  TreeStats bottom;               // all bottom-level BVHs together
  TreeStats top;                  // the top level (empty with a single bottom level)
  std::size_t bottom_levels = 0;
  std::string isa;                // the kernel in use: "AVX-512VL", "AVX2" or "SSE2"
};

std::unique_ptr<Accelerator> build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag,
                                   const Options& options = {});

// The tree statistics of an accelerator made by build() above; nullptr for
// any other backend.
const SceneTreeStats* tree_stats(const Accelerator& accel);

// A 64-bit hash (FNV-1a) of the whole traversal layout of an accelerator made
// by build(): every node, leaf block and primitive record (object ids, not
// addresses). Equal layouts give equal fingerprints; used to check that the
// build does not depend on the thread count. 0 for any other backend.
uint64_t layout_fingerprint(const Accelerator& accel);

}  // namespace pt::bvh
