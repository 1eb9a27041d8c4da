#include "accel/bvh/presplit.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/float_util.h"

namespace pt::bvh {

namespace {

struct Vec3d {
  double v[3];
};

struct Box3d {
  double lo[3], hi[3];
};

// A convex polygon: a triangle clipped by up to six planes has at most 9 vertices.
struct Polygon {
  Vec3d p[12];
  int n = 0;
};

// The part of `in` with x[axis] <= c (below) or >= c.
Polygon clip(const Polygon& in, int axis, double c, bool below) {
  Polygon out;
  const auto inside = [&](const Vec3d& q) { return below ? q.v[axis] <= c : q.v[axis] >= c; };
  for (int i = 0; i < in.n; ++i) {
    const Vec3d& a = in.p[i];
    const Vec3d& b = in.p[(i + 1) % in.n];
    const bool ia = inside(a), ib = inside(b);
    if (ia) out.p[out.n++] = a;
    if (ia != ib) {
      const double t = (c - a.v[axis]) / (b.v[axis] - a.v[axis]);
      Vec3d q;
      for (int k = 0; k < 3; ++k) q.v[k] = a.v[k] + t * (b.v[k] - a.v[k]);
      q.v[axis] = c;
      out.p[out.n++] = q;
    }
  }
  return out;
}

// The float box of the triangle's part within `region`, padded as
// bounds(mesh, tri) pads and kept within `whole` (that padded box); empty if
// the part is.
Bounds3f part_bounds(const Polygon& tri, const Box3d& region, const Bounds3f& whole) {
  Polygon p = tri;
  for (int a = 0; a < 3 && p.n > 0; ++a) {
    p = clip(p, a, region.lo[a], false);
    if (p.n > 0) p = clip(p, a, region.hi[a], true);
  }
  Bounds3f b;
  if (p.n == 0) return b;
  for (int a = 0; a < 3; ++a) {
    double lo = p.p[0].v[a], hi = lo;
    for (int i = 1; i < p.n; ++i) {
      lo = std::min(lo, p.p[i].v[a]);
      hi = std::max(hi, p.p[i].v[a]);
    }
    b.lo[a] = fp::next_float_down(static_cast<float>(lo));
    b.hi[a] = fp::next_float_up(static_cast<float>(hi));
  }
  b = fp::pad(b);
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::max(b.lo[a], whole.lo[a]);
    b.hi[a] = std::min(b.hi[a], whole.hi[a]);
  }
  return b;
}

// A plane strictly inside (lo, hi) on the coarsest level of the dyadic grid
// over [origin, origin + extent] (planes shared by neighbouring triangles, as
// in Karras and Aila), or NaN if none is found.
double grid_plane(double lo, double hi, double origin, double extent) {
  if (!(extent > 0.0)) return std::nan("");
  const double ulo = (lo - origin) / extent, uhi = (hi - origin) / extent;
  for (int level = 1; level <= 24; ++level) {
    const double cells = std::ldexp(1.0, level);
    const double k = std::floor(uhi * cells);
    const double u = k / cells;
    if (u > ulo && u < uhi) return origin + u * extent;
  }
  return std::nan("");
}

struct Piece {
  Box3d region;
  Bounds3f box;
  bool splittable = true;
};

// Splits the triangle into at most `count` pieces: the piece of largest box
// area, cut on its box's longest axis at a grid plane, until there are
// `count` pieces or none can be cut. Writes the pieces' references; returns
// how many.
int split_triangle(const Polygon& tri, const Bounds3f& whole, uint32_t id, int count, const Bounds3f& mesh_box,
                   PrimRef* out) {
  Piece pieces[kMaxPieces];
  int n = 1;
  for (int a = 0; a < 3; ++a) {
    pieces[0].region.lo[a] = whole.lo[a];
    pieces[0].region.hi[a] = whole.hi[a];
  }
  pieces[0].box = whole;
  while (n < count) {
    int pick = -1;
    float best = -1.0f;
    for (int i = 0; i < n; ++i) {
      const float area = surface_area(pieces[i].box);
      if (pieces[i].splittable && area > best) {
        best = area;
        pick = i;
      }
    }
    if (pick < 0) break;
    Piece& p = pieces[pick];
    const Vec3f e = p.box.extent();
    const int axis = e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
    const double c = grid_plane(p.box.lo[axis], p.box.hi[axis], mesh_box.lo[axis],
                                static_cast<double>(mesh_box.hi[axis]) - mesh_box.lo[axis]);
    Piece left = p, right = p;
    left.region.hi[axis] = c;
    right.region.lo[axis] = c;
    if (!std::isnan(c)) {
      left.box = part_bounds(tri, left.region, whole);
      right.box = part_bounds(tri, right.region, whole);
    }
    if (std::isnan(c) || left.box.empty() || right.box.empty()) {
      p.splittable = false;
      continue;
    }
    p = left;
    pieces[n++] = right;
  }
  for (int i = 0; i < n; ++i) out[i] = PrimRef{pieces[i].box, id};
  return n;
}

Polygon triangle_polygon(const TriangleMesh& mesh, uint32_t tri) {
  Polygon p;
  p.n = 3;
  for (int j = 0; j < 3; ++j) {
    const Vec3f v = mesh.positions[mesh.indices[3 * static_cast<std::size_t>(tri) + j]];
    p.p[j] = Vec3d{{v.x, v.y, v.z}};
  }
  return p;
}

}  // namespace

std::vector<PrimRef> triangle_refs(const TriangleMesh& mesh, float extra) {
  const auto n = static_cast<uint32_t>(mesh.triangle_count());
  std::vector<PrimRef> refs;
  if (!(extra > 0.0f) || n == 0) {
    refs.resize(n);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 4096), [&](const tbb::blocked_range<uint32_t>& r) {
      for (uint32_t i = r.begin(); i != r.end(); ++i) refs[i] = PrimRef{bounds(mesh, i), i};
    });
    return refs;
  }
  // Each triangle's wasted box area (its priority), then its piece count.
  std::vector<float> waste(n);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 4096), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t i = r.begin(); i != r.end(); ++i) {
      const Polygon t = triangle_polygon(mesh, i);
      const Vec3f a(static_cast<float>(t.p[0].v[0]), static_cast<float>(t.p[0].v[1]), static_cast<float>(t.p[0].v[2]));
      const Vec3f b(static_cast<float>(t.p[1].v[0]), static_cast<float>(t.p[1].v[1]), static_cast<float>(t.p[1].v[2]));
      const Vec3f c(static_cast<float>(t.p[2].v[0]), static_cast<float>(t.p[2].v[1]), static_cast<float>(t.p[2].v[2]));
      const float area2 = length(cross(b - a, c - a));  // twice the area
      waste[i] = std::max(0.0f, surface_area(bounds(mesh, i)) - area2);
    }
  });
  double total = 0.0;  // in triangle order: the same sum for any thread count
  for (const float w : waste) total += w;
  std::vector<uint32_t> first(n + 1, 0);
  const double share = total > 0.0 ? static_cast<double>(extra) * n / total : 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    const double pieces = 1.0 + std::floor(share * waste[i]);
    first[i + 1] = first[i] + static_cast<uint32_t>(std::min<double>(pieces, kMaxPieces));
  }
  std::vector<float>().swap(waste);
  refs.resize(first[n]);
  const Bounds3f mesh_box = bounds(mesh);
  std::vector<uint32_t> used(n);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 1024), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t i = r.begin(); i != r.end(); ++i) {
      const Bounds3f whole = bounds(mesh, i);
      const int want = static_cast<int>(first[i + 1] - first[i]);
      used[i] = want == 1 ? (refs[first[i]] = PrimRef{whole, i}, 1u)
                          : static_cast<uint32_t>(split_triangle(triangle_polygon(mesh, i), whole, i, want, mesh_box,
                                                                 &refs[first[i]]));
    }
  });
  // Pieces a triangle could not be cut into: close the gaps, in order.
  uint32_t out = 0;
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t k = 0; k < used[i]; ++k) refs[out++] = refs[first[i] + k];
  }
  refs.resize(out);
  return refs;
}

}  // namespace pt::bvh
