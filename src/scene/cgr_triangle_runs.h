// Long runs of a CGR file's "triangle" shapes become one triangle mesh
// (docs/scene-format.md, "CGR"; docs/bench/scale.md).
//
// The course format has no meshes: a model is written as thousands of
// "triangle" shapes, each with its own copy of one material (the Stanford
// bunny as 69,451 of them). One shape and one material each, the description
// took about 1.3 kB a triangle, and both backends built a structure over
// 69,451 objects. Here, once kMinRun consecutive triangles have equal
// materials, they are one TriangleMesh (3 vertices a triangle, as written)
// with one material, and each further such triangle is appended to it.
//
// What the run keeps: every triangle, intersected and shaded as before (the
// same vertices, a flat normal, no texture coordinates; course materials do not
// emit, so no light changes). What it drops: a shape and a material per
// triangle, and so each triangle's own Cryptomatte object (the run is one,
// "shapes[a-b]"; every later shape is named by its place in the file, as the
// renderer would have named it). Only triangles validation has nothing to say
// about join a run (a zero-area triangle stays a shape of its own, warned about
// at its place), and a problem with the run's material is reported once, at
// its first copy. Shorter runs (hand-written files) are left as they are.
#pragma once

#include <cstddef>

#include "scene/import_context.h"

namespace pt {

class CgrTriangleRuns {
 public:
  static constexpr std::size_t kMinRun = 64;

  // After reading the file's shapes[file_index]: `added` when it is now the
  // last entry of scene.shapes (false: it had an error or was skipped).
  void shape_read(ImportContext& ctx, std::size_t file_index, bool added);
  // After the last shape.
  void finish(ImportContext& ctx);

 private:
  bool joins_run(ImportContext& ctx, const ShapeDesc& s) const;
  void merge_run(ImportContext& ctx);
  void append(ImportContext& ctx);
  void end_run(ImportContext& ctx);

  std::size_t first_shape_ = 0;  // the run's first shape, in scene.shapes
  std::size_t first_file_ = 0;   // its index in the file's "shapes"
  std::size_t length_ = 0;       // triangles in the run; 0: no run
  bool merged_ = false;          // the run is one mesh, scene.shapes[first_shape_]
  bool renamed_ = false;         // a run was merged: later shapes are named by their place in the file
};

}  // namespace pt
