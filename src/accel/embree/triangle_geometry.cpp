#include "accel/embree/triangle_geometry.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cstdint>
#include <functional>

namespace pt::embree {

namespace {

constexpr std::size_t kGrain = 1 << 14;  // triangles per task

std::size_t count_degenerate(const TriangleMesh& m) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m.triangle_count(), kGrain), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t n) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) n += degenerate_triangle(m, t) ? 1 : 0;
        return n;
      },
      std::plus<>());
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

// Shared when no triangle is degenerate; otherwise a copy in which each
// degenerate triangle refers to vertex UINT32_MAX (Embree leaves it out).
bool set_indices(RTCGeometry geom, const TriangleMesh& m, std::size_t degenerate) {
  const std::size_t nt = m.triangle_count();
  if (degenerate == 0) {
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                               3 * sizeof(uint32_t), nt);
    return true;
  }
  auto* dst = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
  if (dst == nullptr) return false;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const bool keep = !degenerate_triangle(m, t);
      for (std::size_t k = 3 * t; k < 3 * t + 3; ++k) dst[k] = keep ? m.indices[k] : UINT32_MAX;
    }
  });
  return false;
}

}  // namespace

RTCGeometry new_triangle_geometry(RTCDevice device, const TriangleMesh& mesh, TriangleBuffers& buffers) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (geom == nullptr) return nullptr;
  buffers.degenerate = count_degenerate(mesh);
  buffers.vertices_shared = set_vertices(geom, mesh);
  buffers.indices_shared = set_indices(geom, mesh, buffers.degenerate);
  return geom;
}

}  // namespace pt::embree
