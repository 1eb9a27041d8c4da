// Peak memory of Assimp's reading of one model file, with a chosen set of
// post-processing steps: where the glTF import's bytes per triangle go
// (docs/bench/scale.md). One reading per process (the peak only grows):
//
//   assimp_peak FILE [flags]     flags: a comma list of triangulate, join, sort, validate, flipuvs
//                                (default: the renderer's set for glTF, all but join), or "none"
//
// Prints the triangles read, the peak RSS (VmHWM) before and after, the bytes
// per triangle the reading added, and the file-backed resident pages (RssFile:
// the libraries' code and constants) before and after, which are part of that
// peak.
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

// A "Name:  123 kB" line of /proc/self/status, in KiB (-1 if absent).
long status_kib(const std::string& name) {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);)
    if (line.rfind(name + ":", 0) == 0) return std::stol(line.substr(name.size() + 1));
  return -1;
}

// The steps named in `list`; false for a name it does not know.
bool flags_of(const std::string& list, unsigned& flags) {
  flags = 0;
  if (list == "none") return true;
  const std::pair<const char*, unsigned> names[] = {
      {"triangulate", aiProcess_Triangulate}, {"join", aiProcess_JoinIdenticalVertices},
      {"sort", aiProcess_SortByPType},        {"validate", aiProcess_ValidateDataStructure},
      {"flipuvs", aiProcess_FlipUVs}};
  std::stringstream s(list);
  for (std::string item; std::getline(s, item, ',');) {
    bool known = false;
    for (const auto& [name, bit] : names) {
      if (item == name) flags |= bit;
      known = known || item == name;
    }
    if (!known) return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: assimp_peak FILE [flags|none]\n");
    return 2;
  }
  unsigned flags = 0;
  if (!flags_of(argc > 2 ? argv[2] : "triangulate,sort,validate,flipuvs", flags)) {
    std::fprintf(stderr, "unknown step in '%s' (triangulate, join, sort, validate, flipuvs, or none)\n", argv[2]);
    return 2;
  }
  const long before = status_kib("VmHWM"), file_before = status_kib("RssFile");
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(argv[1], flags);
  if (scene == nullptr) {
    std::fprintf(stderr, "%s\n", importer.GetErrorString());
    return 1;
  }
  unsigned long triangles = 0, vertices = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    triangles += scene->mMeshes[m]->mNumFaces;
    vertices += scene->mMeshes[m]->mNumVertices;
  }
  const long after = status_kib("VmHWM"), file_after = status_kib("RssFile");
  std::printf("%s flags=%s triangles=%lu vertices=%lu peak_before_kib=%ld peak_after_kib=%ld bytes_per_triangle=%.1f "
              "rss_file_before_kib=%ld rss_file_after_kib=%ld\n",
              argv[1], argc > 2 ? argv[2] : "default", triangles, vertices, before, after,
              1024.0 * static_cast<double>(after - before) / static_cast<double>(triangles), file_before, file_after);
  return 0;
}
