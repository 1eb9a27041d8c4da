// The process's heap between the phases of a run.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string_view>

namespace pt {

// Returns to the system the pages of the heap that hold no live allocation
// (glibc's malloc_trim; nothing elsewhere). Loading a scene frees its staging
// arrays (a reader's copies, Assimp's scene, the doubling growth of the mesh
// arrays) into the heap, where they stay resident; an acceleration structure's
// build takes its large arrays from fresh mappings (Embree always), so without
// this they would stack on the build's peak (docs/bench/scale.md).
void release_free_heap();

// Drops from the process's resident set the pages of the shared libraries
// whose file name contains one of `names` that are read-only and never
// written (their code and constants: the PT_LOAD segments without write
// permission, less the RELRO range; a library with text relocations is
// left alone). They are clean pages of the file, read again from the page
// cache if the library runs again. Assimp's are released by
// release_importer_pages (scene/asset_reader.h): before and after each import
// and once loading is done, so that about 2 MiB touched at every start-up and
// 3 MiB more by a glTF import, clean but counted by peak RSS, sit neither
// under the import's peak nor under the acceleration structure's build
// (docs/bench/scale.md). Returns the bytes advised (0 off Linux).
std::size_t release_library_pages(std::initializer_list<std::string_view> names);

}  // namespace pt
