#include "accel/accelerator.h"


#include "accel/bvh/bvh_accel.h"
#include "accel/embree/embree_accel.h"
#include "accel/unbounded.h"
#include "core/heap.h"

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

bool geometry_usable(const SceneGeometry& geometry) {
  for (const Shape& shape : geometry.shapes) {
    ShapeChecker checker;
    check(shape, checker);
    if (!checker.usable()) return false;
  }
  for (const std::vector<uint32_t>& proto : geometry.prototypes) {
    for (uint32_t s : proto) {
      if (s >= geometry.shapes.size()) return false;
    }
  }
  for (const Instance& inst : geometry.instances) {
    if (inst.prototype >= geometry.prototypes.size()) return false;
  }
  return true;
}

std::unique_ptr<Accelerator> build_accelerator(AccelKind kind, const SceneGeometry& geometry, WorkerPool& pool,
                                               Diagnostics& diag, const CutoutTest* cutouts) {
  release_free_heap();  // what loading freed, so that it does not stay under the build's peak
  std::unique_ptr<Accelerator> backend;
  switch (kind) {
    case AccelKind::Embree:
      backend = embree::build(geometry, pool, diag, cutouts);
      break;
    case AccelKind::Bvh: {
      bvh::Options options;
      options.cutouts = cutouts;
      backend = bvh::build(geometry, pool, diag, options);
      break;
    }
  }
  return with_unbounded_shapes(std::move(backend), geometry, cutouts);  // infinite planes, above both backends
}

}  // namespace pt
