#include "accel/accelerator.h"

#include <cmath>
#include <variant>

#include "accel/bvh/bvh_accel.h"
#include "accel/embree/embree_accel.h"

namespace pt {

bool parse_accel_kind(const std::string& name, AccelKind& out) {
  if (name == "embree") {
    out = AccelKind::Embree;
    return true;
  }
  if (name == "bvh") {
    out = AccelKind::Bvh;
    return true;
  }
  return false;
}

const char* accel_kind_name(AccelKind kind) {
  switch (kind) {
    case AccelKind::Embree: return "embree";
    case AccelKind::Bvh: return "bvh";
  }
  return "unknown";
}

std::vector<std::string> accel_kind_names() { return {"embree", "bvh"}; }

namespace {

std::string shape_label(std::size_t i, const char* kind) {
  return "shape " + std::to_string(i) + " (" + kind + ")";
}

}  // namespace

bool validate_geometry(const SceneGeometry& geometry, Diagnostics& diag) {
  const SourceLocation nowhere;
  bool ok = true;
  for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
    const Shape& shape = geometry.shapes[i];
    if (const auto* s = std::get_if<Sphere>(&shape)) {
      if (!is_finite(s->center) || !std::isfinite(s->radius)) {
        diag.error(nowhere, shape_label(i, "sphere") + ": non-finite centre or radius");
        ok = false;
      }
    } else if (const auto* q = std::get_if<Quad>(&shape)) {
      if (!is_finite(q->v[0]) || !is_finite(q->v[1]) || !is_finite(q->v[2]) || !is_finite(q->v[3])) {
        diag.error(nowhere, shape_label(i, "quad") + ": non-finite corner");
        ok = false;
      }
    } else if (const auto* c = std::get_if<Cylinder>(&shape)) {
      if (!is_finite(c->p0) || !is_finite(c->p1) || !std::isfinite(c->radius)) {
        diag.error(nowhere, shape_label(i, "cylinder") + ": non-finite end point or radius");
        ok = false;
      }
    } else if (const auto* m = std::get_if<TriangleMesh>(&shape)) {
      if (m->indices.size() % 3 != 0) {
        diag.error(nowhere, shape_label(i, "triangle mesh") + ": " + std::to_string(m->indices.size()) +
                                " indices is not a multiple of 3");
        ok = false;
        continue;
      }
      const std::size_t nv = m->positions.size();
      for (std::size_t k = 0; k < m->indices.size(); ++k) {
        if (m->indices[k] >= nv) {
          diag.error(nowhere, shape_label(i, "triangle mesh") + ": triangle " + std::to_string(k / 3) +
                                  " refers to vertex " + std::to_string(m->indices[k]) + " but the mesh has " +
                                  std::to_string(nv) + " vertices");
          ok = false;
          break;
        }
      }
      for (std::size_t k = 0; k < nv; ++k) {
        if (!is_finite(m->positions[k])) {
          diag.error(nowhere, shape_label(i, "triangle mesh") + ": vertex " + std::to_string(k) +
                                  " has a non-finite position");
          ok = false;
          break;
        }
      }
    }
  }
  return ok;
}

std::unique_ptr<Accelerator> build_accelerator(AccelKind kind, const SceneGeometry& geometry, WorkerPool& pool,
                                               Diagnostics& diag) {
  switch (kind) {
    case AccelKind::Embree: return embree::build(geometry, pool, diag);
    case AccelKind::Bvh: return bvh::build(geometry, pool, diag);
  }
  return nullptr;
}

}  // namespace pt
