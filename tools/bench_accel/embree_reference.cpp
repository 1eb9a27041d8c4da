#include "embree_reference.h"

#include <embree3/rtcore.h>

#include <chrono>
#include <limits>
#include <type_traits>
#include <variant>

#include "accel/embree/embree_device.h"
#include "accel/embree/user_geometry.h"
#include "core/parallel.h"
#include "geometry/float_util.h"

namespace pt::bench {

namespace {

// As the Embree backend converts rays: open (tmin, tmax) to Embree's closed
// [tnear, tfar] with tnear >= 0; rays that cannot hit anything are refused.
bool to_embree(const Ray& ray, RTCRay& out) {
  if (!is_finite(ray.origin) || !is_finite(ray.dir) || ray.dir == Vec3f(0.0f)) return false;
  if (!(ray.tmin < ray.tmax)) return false;
  out.org_x = ray.origin.x;
  out.org_y = ray.origin.y;
  out.org_z = ray.origin.z;
  out.dir_x = ray.dir.x;
  out.dir_y = ray.dir.y;
  out.dir_z = ray.dir.z;
  out.tnear = ray.tmin > 0.0f ? fp::next_float_up(ray.tmin) : std::numeric_limits<float>::min();
  out.tfar = fp::next_float_down(ray.tmax);
  if (!(out.tnear <= out.tfar)) return false;
  out.time = 0.0f;
  out.mask = 0xFFFFFFFFu;
  out.id = 0;
  out.flags = 0;
  return true;
}

RTCGeometry native_triangles(RTCDevice device, const TriangleMesh& m) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (geom == nullptr) return nullptr;
  const std::size_t nv = m.positions.size();
  if (m.positions.capacity() > nv) {  // Embree reads 16 bytes per vertex: the spare element covers the last
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(), 0,
                               sizeof(Vec3f), nv);
  } else if (auto* dst = static_cast<Vec3f*>(
                 rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3f), nv))) {
    for (std::size_t i = 0; i < nv; ++i) dst[i] = m.positions[i];
  }
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                             3 * sizeof(uint32_t), m.triangle_count());
  rtcCommitGeometry(geom);
  return geom;
}

class EmbreeReference final : public Accelerator {
 public:
  ~EmbreeReference() override {
    if (scene_ != nullptr) rtcReleaseScene(scene_);
  }

  bool build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag) {
    if (!validate_geometry(geometry, diag)) return false;
    if (!device_.valid()) {
      for (const std::string& e : device_.errors()) diag.error(SourceLocation{}, "Embree: " + e);
      return false;
    }
    scene_ = rtcNewScene(device_.get());
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    std::size_t primitives = 0;
    for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
      RTCGeometry geom = std::visit(
          [&](const auto& shape) -> RTCGeometry {
            if constexpr (std::is_same_v<std::decay_t<decltype(shape)>, TriangleMesh>) {
              primitives += shape.triangle_count();
              return native_triangles(device_.get(), shape);
            } else {
              primitives += 1;
              return embree::new_user_geometry(device_.get(), shape);
            }
          },
          geometry.shapes[i]);
      if (geom == nullptr) break;
      rtcAttachGeometryByID(scene_, geom, static_cast<unsigned>(i));
      rtcReleaseGeometry(geom);
      bounds_.extend(pt::bounds(geometry.shapes[i]));
    }
    const auto start = std::chrono::steady_clock::now();
    pool.run([&] { rtcCommitScene(scene_); });
    const auto stop = std::chrono::steady_clock::now();
    if (device_.has_errors()) {
      for (const std::string& e : device_.errors()) diag.error(SourceLocation{}, "Embree: " + e);
      return false;
    }
    stats_.backend = device_.description() + " native triangles";
    stats_.build_seconds = std::chrono::duration<double>(stop - start).count();
    stats_.memory_bytes = device_.bytes_in_use();
    stats_.primitive_count = primitives;
    return true;
  }

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
  embree::Device device_;  // released after scene_
  RTCScene scene_ = nullptr;
  Bounds3f bounds_;
  AccelStats stats_;
};

}  // namespace

std::unique_ptr<Accelerator> build_embree_reference(const SceneGeometry& geometry, WorkerPool& pool,
                                                    Diagnostics& diag) {
  auto accel = std::make_unique<EmbreeReference>();
  if (!accel->build(geometry, pool, diag)) return nullptr;
  return accel;
}

}  // namespace pt::bench
