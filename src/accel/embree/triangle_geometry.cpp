#include "accel/embree/triangle_geometry.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace pt::embree {

namespace {

// Triangle indices of the degenerate triangles, in order.
std::vector<uint32_t> degenerate_triangles(const TriangleMesh& m) {
  std::vector<uint32_t> out;
  const std::size_t n = m.triangle_count();
  for (std::size_t t = 0; t < n; ++t) {
    if (degenerate_triangle(m, t)) out.push_back(static_cast<uint32_t>(t));
  }
  return out;
}

bool set_vertices(RTCGeometry geom, const TriangleMesh& m) {
  const std::size_t nv = m.positions.size();
  if (m.positions.capacity() > nv) {  // the spare element covers Embree's 16-byte read of the last vertex
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(), 0,
                               sizeof(Vec3f), nv);
    return true;
  }
  auto* dst = static_cast<Vec3f*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3f), nv));
  if (dst != nullptr) std::copy(m.positions.begin(), m.positions.end(), dst);
  return false;
}

bool set_indices(RTCGeometry geom, const TriangleMesh& m, const std::vector<uint32_t>& degenerate) {
  const std::size_t nt = m.triangle_count();
  if (degenerate.empty()) {
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                               3 * sizeof(uint32_t), nt);
    return true;
  }
  auto* dst = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
  if (dst == nullptr) return false;
  std::copy(m.indices.begin(), m.indices.end(), dst);
  for (uint32_t t : degenerate) std::fill_n(dst + 3 * static_cast<std::size_t>(t), 3, UINT32_MAX);
  return false;
}

}  // namespace

RTCGeometry new_triangle_geometry(RTCDevice device, const TriangleMesh& mesh, TriangleBuffers& buffers) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (geom == nullptr) return nullptr;
  const std::vector<uint32_t> degenerate = degenerate_triangles(mesh);
  buffers.degenerate = degenerate.size();
  buffers.vertices_shared = set_vertices(geom, mesh);
  buffers.indices_shared = set_indices(geom, mesh, degenerate);
  return geom;
}

}  // namespace pt::embree
