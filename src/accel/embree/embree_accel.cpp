// Embree 3 backend: Embree's BVH over user geometry calling src/geometry for
// every shape, meshes included (one primitive per triangle), so both backends
// answer with the same watertight routines (docs/geometry.md).
// geomID == object id (rtcAttachGeometryByID), primID == triangle index.
#include "accel/embree/embree_accel.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <variant>

#include "accel/embree/embree_device.h"
#include "accel/embree/user_geometry.h"
#include "core/parallel.h"
#include "geometry/float_util.h"

namespace pt::embree {

namespace {

// All rays and geometries use every mask bit: masks are not used to hide
// objects yet, but are set explicitly so a device built with ray masks
// enabled behaves like one without.
constexpr unsigned kMask = 0xFFFFFFFFu;

// Embree accepts origin and direction components up to FLT_LARGE (1.844e18)
// in magnitude; beyond that its behaviour is undefined (Debian's build asserts).
constexpr float kEmbreeLargest = 1.844e18f;

// Converts our ray (open interval tmin < t < tmax) to Embree's (closed
// interval, tnear >= 0). Returns false for rays that cannot hit anything:
// NaN or infinite origin or direction, zero direction, empty interval; and for
// rays Embree cannot take (a component beyond kEmbreeLargest).
bool to_embree(const Ray& ray, RTCRay& out) {
  if (!is_finite(ray.origin) || !is_finite(ray.dir) || ray.dir == Vec3f(0.0f)) return false;
  if (max_component(abs(ray.origin)) > kEmbreeLargest || max_component(abs(ray.dir)) > kEmbreeLargest) return false;
  if (!(ray.tmin < ray.tmax)) return false;  // also NaN
  out.org_x = ray.origin.x;
  out.org_y = ray.origin.y;
  out.org_z = ray.origin.z;
  out.dir_x = ray.dir.x;
  out.dir_y = ray.dir.y;
  out.dir_z = ray.dir.z;
  // One ulp inside the open interval. A non-positive tmin becomes the smallest
  // normal float (Embree requires tnear >= 0 and FTZ flushes denormals).
  out.tnear = ray.tmin > 0.0f ? fp::next_float_up(ray.tmin) : std::numeric_limits<float>::min();
  out.tfar = fp::next_float_down(ray.tmax);
  if (!(out.tnear <= out.tfar)) return false;
  out.time = 0.0f;
  out.mask = kMask;
  out.id = 0;
  out.flags = 0;
  return true;
}

// Embree's own triangle geometry over the mesh's buffers (MeshTriangles::Native),
// with the cutout filter if it may be cut out.
RTCGeometry native_triangles(RTCDevice device, const TriangleMesh& m, const CutoutGeometry* cutout) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (geom == nullptr) return nullptr;
  const std::size_t nv = m.positions.size();
  if (m.positions.capacity() > nv) {  // Embree reads 16 bytes per vertex: the spare element covers the last
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(), 0,
                               sizeof(Vec3f), nv);
  } else if (auto* dst = static_cast<Vec3f*>(
                 rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3f), nv))) {
    std::copy(m.positions.begin(), m.positions.end(), dst);
  }
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                             3 * sizeof(uint32_t), m.triangle_count());
  if (cutout != nullptr) {
    rtcSetGeometryUserData(geom, const_cast<CutoutGeometry*>(cutout));
    rtcSetGeometryIntersectFilterFunction(geom, &cutout_filter);
    rtcSetGeometryOccludedFilterFunction(geom, &cutout_filter);
  }
  rtcSetGeometryMask(geom, kMask);
  rtcCommitGeometry(geom);
  return geom;
}

class EmbreeAccelerator final : public Accelerator {
 public:
  EmbreeAccelerator(MeshTriangles meshes, const CutoutTest* cutouts) : meshes_(meshes), cutouts_(cutouts) {}
  ~EmbreeAccelerator() override {
    if (scene_ != nullptr) rtcReleaseScene(scene_);
    for (RTCScene s : prototypes_) {
      if (s != nullptr) rtcReleaseScene(s);
    }
  }
  EmbreeAccelerator(const EmbreeAccelerator&) = delete;
  EmbreeAccelerator& operator=(const EmbreeAccelerator&) = delete;

  bool build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag);

  bool intersect(const Ray& ray, Hit& hit) const override {
    RTCRayHit rh;
    if (!to_embree(ray, rh.ray)) return false;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit.t = rh.ray.tfar;
    hit.shape = rh.hit.geomID;
    hit.prim = rh.hit.primID;
    hit.uv = {rh.hit.u, rh.hit.v};
    hit.instance = rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID ? kNoInstance : rh.hit.instID[0] - instance_base_;
    return true;
  }

  bool occluded(const Ray& ray) const override {
    RTCRay r;
    if (!to_embree(ray, r)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(scene_, &context, &r);
    return r.tfar == -kInfinity;
  }

  Bounds3f bounds() const override { return bounds_; }
  AccelStats stats() const override { return stats_; }

 private:
  RTCScene new_scene(Diagnostics& diag);
  bool attach_shape(RTCScene scene, const SceneGeometry& geometry, uint32_t object, Diagnostics& diag);
  const CutoutGeometry* cutout_geometry(const Shape& shape, uint32_t object);
  bool attach_instance(const SceneGeometry& geometry, uint32_t instance, Diagnostics& diag);

  MeshTriangles meshes_;
  const CutoutTest* cutouts_;  // null: the scene has no cutouts
  std::vector<std::unique_ptr<CutoutGeometry>> cutout_geometries_;  // user data of the geometries that may be cut out
  Device device_;  // destroyed after the scenes are released
  RTCScene scene_ = nullptr;
  // One scene per prototype, placed in scene_ by instance geometries with
  // geomID instance_base_ + instance id (the shapes keep their object ids).
  std::vector<RTCScene> prototypes_;
  uint32_t instance_base_ = 0;
  Bounds3f bounds_;
  AccelStats stats_;
};

bool report_device_errors(const Device& device, Diagnostics& diag) {
  if (!device.has_errors()) return false;
  for (const std::string& e : device.errors()) diag.error(SourceLocation{}, "Embree: " + e);
  return true;
}

// A scene with the flags every scene of this backend has. ROBUST: the
// traversal avoids accuracy-reducing shortcuts (node boxes touched only at a
// corner, where a ray aimed at a mesh vertex passes). HIGH: the best tree
// Embree builds over user geometry.
RTCScene EmbreeAccelerator::new_scene(Diagnostics& diag) {
  RTCScene scene = rtcNewScene(device_.get());
  if (scene == nullptr) {
    if (!report_device_errors(device_, diag)) diag.error(SourceLocation{}, "Embree: cannot create a scene");
    return nullptr;
  }
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  return scene;
}

// The user data of a shape that may be cut out (null for any other).
const CutoutGeometry* EmbreeAccelerator::cutout_geometry(const Shape& shape, uint32_t object) {
  if (cutouts_ == nullptr || !cutouts_->may_cut_anywhere(object)) return nullptr;
  auto g = std::make_unique<CutoutGeometry>();
  g->shape = std::visit([](const auto& s) -> const void* { return &s; }, shape);
  g->test = cutouts_;
  g->instance_base = instance_base_;
  cutout_geometries_.push_back(std::move(g));
  return cutout_geometries_.back().get();
}

bool EmbreeAccelerator::attach_shape(RTCScene scene, const SceneGeometry& geometry, uint32_t object,
                                     Diagnostics& diag) {
  const Shape& shape = geometry.shapes[object];
  const auto* mesh = std::get_if<TriangleMesh>(&shape);
  const CutoutGeometry* cutout = cutout_geometry(shape, object);
  RTCGeometry geom = mesh != nullptr && meshes_ == MeshTriangles::Native
                         ? native_triangles(device_.get(), *mesh, cutout)
                         : new_user_geometry(device_.get(), shape, cutout);
  if (geom == nullptr) {
    if (!report_device_errors(device_, diag)) {
      diag.error(SourceLocation{}, "Embree: cannot create the geometry of shape " + std::to_string(object));
    }
    return false;
  }
  rtcAttachGeometryByID(scene, geom, object);
  rtcReleaseGeometry(geom);
  return true;
}

bool EmbreeAccelerator::attach_instance(const SceneGeometry& geometry, uint32_t instance, Diagnostics& diag) {
  const Instance& inst = geometry.instances[instance];
  RTCGeometry geom = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
  if (geom == nullptr) {
    if (!report_device_errors(device_, diag)) diag.error(SourceLocation{}, "Embree: cannot create an instance");
    return false;
  }
  rtcSetGeometryInstancedScene(geom, prototypes_[inst.prototype]);
  rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, &inst.transform.m[0][0]);
  rtcSetGeometryMask(geom, kMask);
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(scene_, geom, instance_base_ + instance);
  rtcReleaseGeometry(geom);
  return true;
}

bool EmbreeAccelerator::build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag) {
  if (report_device_errors(device_, diag) || !device_.valid()) return false;
  assert(geometry_usable(geometry));  // Embree must never see NaN bounds or bad indices
  scene_ = new_scene(diag);
  if (scene_ == nullptr) return false;
  instance_base_ = static_cast<uint32_t>(geometry.shapes.size());
  std::size_t primitives = 0;
  const std::vector<bool> direct = placed_directly(geometry);
  for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
    primitives += primitive_count(geometry.shapes[i]);
    if (direct[i] && !attach_shape(scene_, geometry, static_cast<uint32_t>(i), diag)) return false;
  }
  for (const std::vector<uint32_t>& proto : geometry.prototypes) {
    prototypes_.push_back(new_scene(diag));
    if (prototypes_.back() == nullptr) return false;
    for (uint32_t s : proto) {
      if (!attach_shape(prototypes_.back(), geometry, s, diag)) return false;
    }
  }
  bounds_ = world_bounds(geometry);

  const auto start = std::chrono::steady_clock::now();
  // Embree's TBB tasking runs the parallel build inside the pool's arena.
  bool ok = true;
  pool.run([&] {
    for (RTCScene p : prototypes_) rtcCommitScene(p);
    for (std::size_t i = 0; i < geometry.instances.size() && ok; ++i) {
      ok = attach_instance(geometry, static_cast<uint32_t>(i), diag);
    }
    if (ok) rtcCommitScene(scene_);
  });
  const auto stop = std::chrono::steady_clock::now();
  if (!ok || report_device_errors(device_, diag)) return false;

  stats_.backend = device_.description() + (meshes_ == MeshTriangles::Native ? " native triangles" : "");
  stats_.build_seconds = std::chrono::duration<double>(stop - start).count();
  stats_.memory_bytes = device_.bytes_in_use();
  stats_.primitive_count = primitives;
  return true;
}

}  // namespace

std::unique_ptr<Accelerator> build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag,
                                   MeshTriangles meshes, const CutoutTest* cutouts) {
  auto accel = std::make_unique<EmbreeAccelerator>(meshes, cutouts);
  if (!accel->build(geometry, pool, diag)) return nullptr;
  return accel;
}

}  // namespace pt::embree
