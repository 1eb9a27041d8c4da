#include "scene/cgr_triangle_runs.h"

#include <string>
#include <utility>
#include <variant>

namespace pt {
namespace {

// A file's "triangle" as the CGR importer makes it, which validation accepts
// without a word: a one-triangle mesh of non-zero area, with no name,
// transform or field locations to lose.
const TriangleMesh* plain_triangle(const ShapeDesc& s) {
  if (s.type != "triangle" || !s.name.empty() || s.transform || !s.fields.empty()) return nullptr;
  const auto* m = std::get_if<TriangleMesh>(&s.geometry);
  if (!m || m->positions.size() != 3 || m->indices.size() != 3 || !m->normals.empty() || !m->uvs.empty())
    return nullptr;
  return zero_area_triangle(m->positions[0], m->positions[1], m->positions[2]) ? nullptr : m;
}

// The values read_material (import_cgr.cpp) sets, compared; locations and names aside.
bool same_values(const MaterialDesc& a, const MaterialDesc& b) {
  return a.type.value == b.type.value && a.kd.value == b.kd.value && a.ks.value == b.ks.value &&
         a.diffuse.value == b.diffuse.value && a.specular.value == b.specular.value &&
         a.exponent.value == b.exponent.value && a.reflectivity.value == b.reflectivity.value &&
         a.refractive.value == b.refractive.value && a.ior.value == b.ior.value && !a.ka && !b.ka &&
         a.emission.value == RGB(0.0f) && b.emission.value == RGB(0.0f);
}

// Whether shapes with materials a and b may share one: the same material, or
// two inline materials (never the default one) with the same values.
bool same_material(const ImportContext& ctx, int a, int b) {
  if (a == b) return true;
  if (ctx.default_material && (a == *ctx.default_material || b == *ctx.default_material)) return false;
  const auto& m = ctx.scene.materials;
  return same_values(m[static_cast<std::size_t>(a)], m[static_cast<std::size_t>(b)]);
}

void add_triangle(TriangleMesh& mesh, const TriangleMesh& t) {
  const auto base = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), t.positions.begin(), t.positions.end());
  for (uint32_t i = 0; i < 3; ++i) mesh.indices.push_back(base + i);
}

}  // namespace

bool CgrTriangleRuns::joins_run(ImportContext& ctx, const ShapeDesc& s) const {
  return length_ > 0 && same_material(ctx, ctx.scene.shapes[first_shape_].material, s.material);
}

void CgrTriangleRuns::shape_read(ImportContext& ctx, std::size_t file_index, bool added) {
  auto& shapes = ctx.scene.shapes;
  if (!added) return end_run(ctx);
  const bool plain = plain_triangle(shapes.back()) != nullptr;
  const bool joins = plain && joins_run(ctx, shapes.back());
  if (renamed_) shapes.back().name = "shapes[" + std::to_string(file_index) + "]";
  if (joins) {
    ++length_;
    if (merged_) return append(ctx);
    if (length_ == kMinRun) merge_run(ctx);
    return;
  }
  end_run(ctx);
  if (plain) {
    first_shape_ = shapes.size() - 1;
    first_file_ = file_index;
    length_ = 1;
  }
}

// The run's materials are either all one (the default material) or its
// triangles' own copies, the last entries of scene.materials: the copies
// after the first are dropped.
void CgrTriangleRuns::merge_run(ImportContext& ctx) {
  auto& shapes = ctx.scene.shapes;
  auto& materials = ctx.scene.materials;
  const int first_material = shapes[first_shape_].material;
  bool shared = true, copies = materials.size() == static_cast<std::size_t>(first_material) + length_;
  for (std::size_t k = 0; k < length_; ++k) {
    const int m = shapes[first_shape_ + k].material;
    shared = shared && m == first_material;
    copies = copies && m == first_material + static_cast<int>(k);
  }
  if (!shared && !copies) {  // not a layout this importer makes: left as it is
    length_ = 0;
    return;
  }
  if (copies) materials.resize(static_cast<std::size_t>(first_material) + 1);
  TriangleMesh mesh;
  for (std::size_t k = 0; k < length_; ++k) add_triangle(mesh, std::get<TriangleMesh>(shapes[first_shape_ + k].geometry));
  shapes[first_shape_].geometry = std::move(mesh);
  shapes.resize(first_shape_ + 1);
  merged_ = renamed_ = true;
}

void CgrTriangleRuns::append(ImportContext& ctx) {
  auto& shapes = ctx.scene.shapes;
  ShapeDesc& run = shapes[first_shape_];
  auto& materials = ctx.scene.materials;
  const auto own = static_cast<std::size_t>(shapes.back().material);
  if (shapes.back().material != run.material && own + 1 == materials.size()) materials.pop_back();  // its own copy
  add_triangle(std::get<TriangleMesh>(run.geometry), std::get<TriangleMesh>(shapes.back().geometry));
  shapes.pop_back();
}

// The mesh's arrays keep the capacity they grew to: shrinking would copy them,
// and in a large one (mapped, not in the heap) the pages past its size were
// never written, so they take no memory.
void CgrTriangleRuns::end_run(ImportContext& ctx) {
  if (merged_) {
    ctx.scene.shapes[first_shape_].name =
        "shapes[" + std::to_string(first_file_) + "-" + std::to_string(first_file_ + length_ - 1) + "]";
  }
  length_ = 0;
  merged_ = false;
}

void CgrTriangleRuns::finish(ImportContext& ctx) { end_run(ctx); }

}  // namespace pt
