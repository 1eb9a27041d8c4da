// The process's heap between the phases of a run.
#pragma once

namespace pt {

// Returns to the system the pages of the heap that hold no live allocation
// (glibc's malloc_trim; nothing elsewhere). Loading a scene frees its staging
// arrays (a reader's copies, Assimp's scene, the doubling growth of the mesh
// arrays) into the heap, where they stay resident; an acceleration structure's
// build takes its large arrays from fresh mappings (Embree always), so without
// this they would stack on the build's peak (docs/bench/scale.md).
void release_free_heap();

}  // namespace pt
