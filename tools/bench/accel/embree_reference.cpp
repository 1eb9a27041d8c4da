#include "embree_reference.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "accel/embree/user_geometry.h"
#include "core/parallel.h"

namespace pt::bench {

namespace {

// Embree's triangles over the mesh's own buffers; a copy of the vertices only
// where Embree's 16-byte read of the last one would leave the vector.
RTCGeometry triangles(RTCDevice device, const TriangleMesh& m) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (geom == nullptr) return nullptr;
  const std::size_t nv = m.positions.size();
  if (m.positions.capacity() > nv) {
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(), 0,
                               sizeof(Vec3f), nv);
  } else if (auto* dst = static_cast<Vec3f*>(
                 rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3f), nv))) {
    std::copy(m.positions.begin(), m.positions.end(), dst);
  }
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                             3 * sizeof(uint32_t), m.triangle_count());
  return geom;
}

}  // namespace

BareEmbree::~BareEmbree() {
  if (scene_ != nullptr) rtcReleaseScene(scene_);
  for (RTCScene s : prototypes_) {
    if (s != nullptr) rtcReleaseScene(s);
  }
}

RTCScene BareEmbree::new_scene() const {
  RTCScene scene = rtcNewScene(device_.get());
  if (scene == nullptr) return nullptr;
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  return scene;
}

bool BareEmbree::attach(RTCScene scene, const SceneGeometry& geometry, uint32_t object) {
  const Shape& shape = geometry.shapes[object];
  const auto* mesh = std::get_if<TriangleMesh>(&shape);
  RTCGeometry geom = mesh != nullptr ? triangles(device_.get(), *mesh) : embree::new_user_geometry(device_.get(), shape);
  if (geom == nullptr) return false;
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(scene, geom, object);
  rtcReleaseGeometry(geom);
  return true;
}

bool BareEmbree::build(const SceneGeometry& geometry, WorkerPool& pool, Diagnostics& diag) {
  auto fail = [&](const std::string& what) {
    std::string why;
    for (const std::string& e : device_.errors()) why += "; " + e;
    diag.error(SourceLocation{}, "bare Embree: " + what + why);
    return false;
  };
  if (!device_.valid() || (scene_ = new_scene()) == nullptr) return fail("cannot create a device or scene");
  const std::vector<bool> direct = placed_directly(geometry);
  for (std::size_t i = 0; i < geometry.shapes.size(); ++i) {
    stats_.primitive_count += primitive_count(geometry.shapes[i]);
    if (direct[i] && !attach(scene_, geometry, static_cast<uint32_t>(i))) return fail("cannot create a geometry");
  }
  for (const std::vector<uint32_t>& proto : geometry.prototypes) {
    prototypes_.push_back(new_scene());
    if (prototypes_.back() == nullptr) return fail("cannot create a scene");
    for (uint32_t s : proto) {
      if (!attach(prototypes_.back(), geometry, s)) return fail("cannot create a geometry");
    }
  }
  instance_base_ = static_cast<uint32_t>(geometry.shapes.size());
  bounds_ = world_bounds(geometry);
  const auto start = std::chrono::steady_clock::now();
  pool.run([&] {
    for (RTCScene p : prototypes_) rtcCommitScene(p);
    for (std::size_t i = 0; i < geometry.instances.size(); ++i) {
      const Instance& inst = geometry.instances[i];
      RTCGeometry geom = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(geom, prototypes_[inst.prototype]);
      rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, &inst.transform.m[0][0]);
      rtcCommitGeometry(geom);
      rtcAttachGeometryByID(scene_, geom, instance_base_ + static_cast<uint32_t>(i));
      rtcReleaseGeometry(geom);
    }
    rtcCommitScene(scene_);
  });
  const auto stop = std::chrono::steady_clock::now();
  if (device_.has_errors()) return fail("build failed");
  stats_.backend = device_.description() + " bare";
  stats_.build_seconds = std::chrono::duration<double>(stop - start).count();
  stats_.memory_bytes = device_.bytes_in_use();
  return true;
}

std::unique_ptr<BareEmbree> build_embree_reference(const SceneGeometry& geometry, WorkerPool& pool,
                                                   Diagnostics& diag) {
  auto accel = std::make_unique<BareEmbree>();
  if (!accel->build(geometry, pool, diag)) return nullptr;
  return accel;
}

}  // namespace pt::bench
