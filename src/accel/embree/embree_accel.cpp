// Embree 3 backend: meshes are Embree's own triangle geometry (its SIMD
// triangle test; triangle_geometry.h), the analytic shapes user geometry
// calling src/geometry (user_geometry.h); transforms are Embree instances.
// geomID == object id (rtcAttachGeometryByID), primID == triangle index.
// Where Embree's triangle test and ours differ, and by how much: docs/geometry.md.
#include "accel/embree/embree_accel.h"

#include <embree3/rtcore.h>

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <variant>

#include "accel/embree/compact.h"
#include "accel/embree/embree_device.h"
#include "accel/embree/queries.h"
#include "accel/embree/triangle_geometry.h"
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
// interval, tnear >= 0). Returns false, leaving `out` unspecified, for rays
// that cannot hit anything: NaN or infinite origin or direction, zero
// direction, empty interval (tmin < tmax false, also for NaN); and for rays
// Embree cannot take (an origin or direction component beyond kEmbreeLargest).
//
// This runs for every ray (a camera ray of a five-shape scene costs Embree
// about 90 ns), so it tests the Ray's eight floats as two SSE vectors, and
// writes the RTCRay as Embree reads it (store_ray, queries.h).
inline bool to_embree(const Ray& ray, RTCRay& out) {
  static_assert(sizeof(Ray) == 8 * sizeof(float) && offsetof(Ray, dir) == 3 * sizeof(float) &&
                offsetof(Ray, tmin) == 6 * sizeof(float));
  const __m128 org = _mm_loadu_ps(&ray.origin.x);  // ox oy oz dx
  const __m128 dir = _mm_loadu_ps(&ray.dir.x);     // dx dy dz tmin
  const __m128 magnitude = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  // Six components within kEmbreeLargest (a comparison with NaN is false), and
  // tmin not NaN (|tmin| <= inf): one mask of four lanes.
  const __m128 in_range = _mm_and_ps(_mm_cmple_ps(_mm_and_ps(org, magnitude), _mm_set1_ps(kEmbreeLargest)),
                                     _mm_cmple_ps(_mm_and_ps(dir, magnitude),
                                                  _mm_setr_ps(kEmbreeLargest, kEmbreeLargest, kEmbreeLargest, kInfinity)));
  const bool zero_dir = (_mm_movemask_ps(_mm_cmpeq_ps(dir, _mm_setzero_ps())) & 7) == 7;
  if (_mm_movemask_ps(in_range) != 0xf || zero_dir || !(ray.tmin < ray.tmax)) return false;
  // One ulp inside the open interval. A non-positive tmin becomes the smallest
  // normal float (Embree requires tnear >= 0 and FTZ flushes denormals). An
  // infinite tmax stays infinite: Embree never reports a hit at t = inf.
  if (!(ray.tmax > std::numeric_limits<float>::min())) return false;  // nothing lies in (0, tmax)
  const float tnear = ray.tmin > 0.0f ? fp::next_float_up(ray.tmin) : std::numeric_limits<float>::min();
  const uint32_t tmax_bits = std::bit_cast<uint32_t>(ray.tmax);
  const uint32_t tfar_bits = ray.tmax < kInfinity ? tmax_bits - 1 : tmax_bits;
  if (!(tnear <= std::bit_cast<float>(tfar_bits))) return false;
  // (org, tnear): tnear into lane 3.
  const __m128 keep3 = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
  const __m128 tnear3 = _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(_mm_set_ss(tnear)), 12));
  store_ray(out, _mm_or_ps(_mm_and_ps(org, keep3), tnear3), dir, tfar_bits);
  return true;
}

// The geometry of one shape, not yet committed: Embree's triangles for a mesh
// (with the cutout filter if it may be cut out), user geometry for everything
// else (whose callbacks apply the cutout test themselves).
RTCGeometry new_geometry(RTCDevice device, const Shape& shape, const CutoutGeometry* cutout,
                         TriangleBuffers& buffers) {
  if (const auto* mesh = std::get_if<TriangleMesh>(&shape)) {
    RTCGeometry geom = new_triangle_geometry(device, *mesh, buffers);
    if (geom != nullptr && cutout != nullptr) {
      rtcSetGeometryUserData(geom, const_cast<CutoutGeometry*>(cutout));
      rtcSetGeometryIntersectFilterFunction(geom, &cutout_filter);
      rtcSetGeometryOccludedFilterFunction(geom, &cutout_filter);
    }
    return geom;
  }
  return new_user_geometry(device, shape, cutout);
}

class EmbreeAccelerator final : public Accelerator {
 public:
  explicit EmbreeAccelerator(const CutoutTest* cutouts) : cutouts_(cutouts) {}
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
    return to_embree(ray, rh.ray) && intersect1(scene_, rh, instance_base_, hit);
  }

  bool occluded(const Ray& ray) const override {
    RTCRay r;
    return to_embree(ray, r) && occluded1(scene_, r);
  }

  Bounds3f bounds() const override { return bounds_; }
  AccelStats stats() const override { return stats_; }

 private:
  RTCScene new_scene(Diagnostics& diag);
  bool attach_shapes(const SceneGeometry& geometry, Diagnostics& diag);
  bool attach_shape(RTCScene scene, const SceneGeometry& geometry, uint32_t object, Diagnostics& diag);
  const CutoutGeometry* cutout_geometry(const Shape& shape, uint32_t object);
  bool attach_instance(const SceneGeometry& geometry, uint32_t instance, Diagnostics& diag);

  const CutoutTest* cutouts_;  // null: the scene has no cutouts
  std::vector<std::unique_ptr<CutoutGeometry>> cutout_geometries_;  // user data of the geometries that may be cut out
  Device device_;  // destroyed after the scenes are released
  RTCScene scene_ = nullptr;
  // One scene per prototype, placed in scene_ by instance geometries with
  // geomID instance_base_ + instance id (the shapes keep their object ids).
  std::vector<RTCScene> prototypes_;
  uint32_t instance_base_ = 0;
  bool compact_ = false;  // scenes built with RTC_SCENE_FLAG_COMPACT (new_scene)
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
// corner, where a ray aimed at a mesh vertex passes), and triangles are tested
// with Embree's Plücker test, watertight along shared edges. HIGH: the best
// build quality (with ROBUST, Embree 3.13 builds its binned SAH tree, not the
// spatial-split one). COMPACT, only for scenes of kEmbreeCompactTriangles or
// more: 4-wide nodes over indexed triangles (leaves refer to the shared vertex
// buffer instead of copying the vertices), which halves the build's peak
// memory (10M triangles: 53 instead of 107 bytes a triangle above the
// process's baseline, docs/bench/scale.md). Embree's device option
// tri_accel=bvh8.triangle4i would give 8-wide nodes over indexed triangles,
// but with its non-robust test (rays aimed at vertices pass; docs/geometry.md).
RTCScene EmbreeAccelerator::new_scene(Diagnostics& diag) {
  RTCScene scene = rtcNewScene(device_.get());
  if (scene == nullptr) {
    if (!report_device_errors(device_, diag)) diag.error(SourceLocation{}, "Embree: cannot create a scene");
    return nullptr;
  }
  rtcSetSceneFlags(scene, compact_ ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT : RTC_SCENE_FLAG_ROBUST);
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
  TriangleBuffers buffers;
  RTCGeometry geom = new_geometry(device_.get(), shape, cutout_geometry(shape, object), buffers);
  if (geom == nullptr) {
    if (!report_device_errors(device_, diag)) {
      diag.error(SourceLocation{}, "Embree: cannot create the geometry of shape " + std::to_string(object));
    }
    return false;
  }
  // What every geometry gets, whatever its type. A per-geometry filter function
  // (e.g. alpha cutouts: rtcSetGeometryIntersectFilterFunction and
  // rtcSetGeometryOccludedFilterFunction, with rtcSetGeometryUserData on a
  // triangle geometry, whose user data is free) is set here, before the commit;
  // user geometry's callbacks would have to call rtcFilterIntersection /
  // rtcFilterOcclusion for it to run.
  rtcSetGeometryMask(geom, kMask);
  rtcCommitGeometry(geom);
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

// Every shape into its scene: direct shapes into scene_, each prototype's into
// a scene of its own.
bool EmbreeAccelerator::attach_shapes(const SceneGeometry& geometry, Diagnostics& diag) {
  const std::vector<bool> direct = placed_directly(geometry);
  for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
    if (direct[i] && !attach_shape(scene_, geometry, static_cast<uint32_t>(i), diag)) return false;
  }
  for (const std::vector<uint32_t>& proto : geometry.prototypes) {
    prototypes_.push_back(new_scene(diag));
    if (prototypes_.back() == nullptr) return false;
    for (uint32_t s : proto) {
      if (!attach_shape(prototypes_.back(), geometry, s, diag)) return false;
    }
  }
  return true;
}

bool EmbreeAccelerator::build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag) {
  if (report_device_errors(device_, diag) || !device_.valid()) return false;
  assert(geometry_usable(geometry));  // Embree must never see NaN bounds or bad indices
  std::size_t triangles = 0;
  for (const Shape& shape : geometry.shapes)
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape)) triangles += mesh->triangle_count();
  compact_ = triangles >= kEmbreeCompactTriangles;
  scene_ = new_scene(diag);
  if (scene_ == nullptr) return false;
  instance_base_ = static_cast<uint32_t>(geometry.shapes.size());
  bounds_ = world_bounds(geometry);

  const auto start = std::chrono::steady_clock::now();
  // Inside the pool's arena: the meshes' parallel preparation
  // (triangle_geometry.cpp) and Embree's TBB-tasking build.
  bool ok = true;
  pool.run([&] {
    ok = attach_shapes(geometry, diag);
    if (!ok) return;
    for (RTCScene p : prototypes_) rtcCommitScene(p);
    for (std::size_t i = 0; i < geometry.instances.size() && ok; ++i) {
      ok = attach_instance(geometry, static_cast<uint32_t>(i), diag);
    }
    if (ok) rtcCommitScene(scene_);
  });
  const auto stop = std::chrono::steady_clock::now();
  if (!ok || report_device_errors(device_, diag)) return false;

  stats_.backend = device_.description();
  stats_.build_seconds = std::chrono::duration<double>(stop - start).count();
  stats_.memory_bytes = device_.bytes_in_use();
  stats_.build_peak_bytes = device_.peak_bytes();
  for (const Shape& shape : geometry.shapes) stats_.primitive_count += primitive_count(shape);
  return true;
}

}  // namespace

std::unique_ptr<Accelerator> build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag,
                                   const CutoutTest* cutouts) {
  auto accel = std::make_unique<EmbreeAccelerator>(cutouts);
  if (!accel->build(geometry, pool, diag)) return nullptr;
  return accel;
}

}  // namespace pt::embree
