#include "cross_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <variant>

#include <tbb/parallel_for.h>

#include "core/parallel.h"

namespace pt::bench {

namespace {

// One ray's comparison.
struct Outcome {
  Verdict verdict = Verdict::Agree;
  Cause cause = Cause::Other;  // for HitMiss and Distance
  bool compared = false;       // an agreeing hit pair
  double relative_t = 0;       // |ta - tb| / scale for an agreeing hit pair
};

struct D3 {
  double x, y, z;
};
D3 d3(Vec3f v) { return {v.x, v.y, v.z}; }
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 cross3(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot3(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// Where the ray's line passes a triangle, in double precision.
struct TrianglePass {
  int on_boundary = 0;    // barycentrics within kBoundary of 0: 1 = an edge, 2 = a vertex
  double cosine = 0;      // |cos| of the angle between the ray and the triangle's normal
  double farthest = 0;    // the distance of the farthest corner from the origin, in units of |dir|
};

TrianglePass pass_of(const TriangleMesh& m, uint32_t tri, const Ray& ray) {
  TrianglePass out;
  const uint32_t* idx = &m.indices[3 * static_cast<std::size_t>(tri)];
  const D3 o = d3(ray.origin), d = d3(ray.dir);
  const D3 p0 = d3(m.positions[idx[0]]), p1 = d3(m.positions[idx[1]]), p2 = d3(m.positions[idx[2]]);
  const D3 e1 = sub(p1, p0), e2 = sub(p2, p0), n = cross3(e1, e2), pvec = cross3(d, e2);
  out.cosine = std::fabs(dot3(n, d)) / std::sqrt(dot3(n, n) * dot3(d, d));
  for (const D3& p : {p0, p1, p2}) out.farthest = std::max(out.farthest, std::sqrt(dot3(sub(p, o), sub(p, o)) / dot3(d, d)));
  const double det = dot3(e1, pvec);
  if (det == 0.0 || !std::isfinite(det)) return out;
  const D3 tvec = sub(o, p0);
  const double u = dot3(tvec, pvec) / det, v = dot3(d, cross3(tvec, e1)) / det;
  out.on_boundary = (std::fabs(u) <= kBoundary) + (std::fabs(v) <= kBoundary) + (std::fabs(1.0 - u - v) <= kBoundary);
  return out;
}

// The cause a hit gives for a disagreement (cross_check.h): where on its
// triangle the ray's line passes, or where along the ray the hit lies.
Cause cause_of(const SceneGeometry& g, const Ray& world, const Hit& h) {
  const double start = std::max(0.0f, world.tmin);
  const double scale = std::max(1.0, static_cast<double>(length(world.origin) / length(world.dir)));
  double near_start = 1e-4 * scale;
  if (const auto* m = std::get_if<TriangleMesh>(&g.shapes[h.shape])) {
    const Ray ray = h.instance == kNoInstance ? world : g.instances[h.instance].transform.to_object(world);
    const TrianglePass p = pass_of(*m, h.prim, ray);
    if (p.on_boundary >= 2) return Cause::Vertex;
    if (p.on_boundary == 1) return Cause::Edge;
    if (!(p.cosine > 1e-3)) return Cause::Grazing;
    near_start = std::max(near_start, 1e-2 * p.farthest);
  }
  if (h.t - start <= near_start) return Cause::RayStart;
  if (std::isfinite(world.tmax) && world.tmax - h.t <= 1e-4 * std::max(1.0, static_cast<double>(world.tmax))) {
    return Cause::RayEnd;
  }
  return Cause::Other;
}

Outcome compare_nearest(const Accelerator& a, const Accelerator& b, const SceneGeometry& g, const Ray& ray,
                        float tolerance) {
  Outcome o;
  Hit ha, hb;
  const bool fa = a.intersect(ray, ha), fb = b.intersect(ray, hb);
  if (fa != fb) {
    o.verdict = Verdict::HitMiss;
    o.cause = cause_of(g, ray, fa ? ha : hb);
    return o;
  }
  if (!fa) return o;
  const float scale = std::max({ha.t, hb.t, length(ray.origin) / length(ray.dir), 1e-3f});
  // The same primitive of another placement of the same object is a different surface.
  const bool same = ha.shape == hb.shape && ha.prim == hb.prim && ha.instance == hb.instance;
  if (!(std::fabs(ha.t - hb.t) <= tolerance * scale)) {
    o.verdict = Verdict::Distance;
    if (same) {
      o.cause = Cause::SameTriangle;
    } else {
      // The nearer hit is the one the other backend did not report.
      const Hit& nearer = ha.t < hb.t ? ha : hb;
      const Hit& farther = ha.t < hb.t ? hb : ha;
      o.cause = cause_of(g, ray, nearer);
      if (o.cause == Cause::Other) o.cause = cause_of(g, ray, farther);
    }
    return o;
  }
  o.verdict = same ? Verdict::Agree : Verdict::Tie;
  o.compared = same;
  o.relative_t = std::fabs(static_cast<double>(ha.t) - hb.t) / scale;
  return o;
}

Outcome compare_any(const Accelerator& a, const Accelerator& b, const SceneGeometry& g, const Ray& ray) {
  Outcome o;
  const bool oa = a.occluded(ray), ob = b.occluded(ray);
  if (oa == ob) return o;
  o.verdict = Verdict::HitMiss;
  Hit h;
  if ((oa ? a : b).intersect(ray, h)) o.cause = cause_of(g, ray, h);
  return o;
}

void tally(CrossCheckCounts& c, const Outcome& o) {
  ++c.rays;
  switch (o.verdict) {
    case Verdict::Agree: ++c.agree; break;
    case Verdict::Tie: ++c.tie; break;
    case Verdict::HitMiss: ++c.hit_miss; break;
    case Verdict::Distance: ++c.distance; break;
  }
  if (o.verdict == Verdict::HitMiss || o.verdict == Verdict::Distance) ++c.cause[static_cast<std::size_t>(o.cause)];
  if (o.compared) {
    ++c.hits_compared;
    if (o.relative_t > 0) ++c.t_differs;
    c.max_relative_t = std::max(c.max_relative_t, o.relative_t);
  }
}

int severity(Verdict v) {
  switch (v) {
    case Verdict::Agree: return 0;
    case Verdict::Tie: return 1;
    case Verdict::Distance: return 2;
    case Verdict::HitMiss: return 3;
  }
  return 0;
}

void check_set(const RaySet& set, bool any_hit, const Accelerator& a, const Accelerator& b, const SceneGeometry& g,
               WorkerPool& pool, float tolerance, CrossCheckCounts& counts, std::vector<Verdict>& pixel) {
  std::vector<Outcome> outcome(set.rays.size());
  pool.run([&] {
    tbb::parallel_for(std::size_t{0}, set.rays.size(), [&](std::size_t i) {
      outcome[i] = any_hit ? compare_any(a, b, g, set.rays[i]) : compare_nearest(a, b, g, set.rays[i], tolerance);
    });
  });
  for (std::size_t i = 0; i < outcome.size(); ++i) {
    tally(counts, outcome[i]);
    Verdict& p = pixel[set.pixel[i]];
    if (severity(outcome[i].verdict) > severity(p)) p = outcome[i].verdict;
  }
}

}  // namespace

std::string thousands(std::size_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

const char* cause_name(Cause c) {
  switch (c) {
    case Cause::Vertex: return "vertex";
    case Cause::Edge: return "edge";
    case Cause::Grazing: return "grazing";
    case Cause::RayStart: return "ray start";
    case Cause::RayEnd: return "ray end";
    case Cause::SameTriangle: return "same triangle, t";
    case Cause::Other: return "other";
  }
  return "?";
}

CrossCheck cross_check(const Accelerator& a, const Accelerator& b, const SceneGeometry& geometry, const RaySets& rays,
                       WorkerPool& pool, float tolerance) {
  CrossCheck check;
  check.tolerance = tolerance;
  check.width = rays.width;
  check.height = rays.height;
  check.pixel.assign(static_cast<std::size_t>(rays.width) * static_cast<std::size_t>(rays.height), Verdict::Agree);
  check_set(rays.camera, false, a, b, geometry, pool, tolerance, check.camera, check.pixel);
  check_set(rays.shadow, true, a, b, geometry, pool, tolerance, check.shadow, check.pixel);
  check_set(rays.diffuse, false, a, b, geometry, pool, tolerance, check.diffuse, check.pixel);
  return check;
}

std::string describe_rate(const CrossCheck& check) {
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.2g%%", 100.0 * check.rate());
  std::string s = std::string(rate) + " (" + thousands(check.disagreements()) + " of " + thousands(check.rays()) +
                  " rays";
  std::string causes;
  for (int k = 0; k < kCauses; ++k) {
    const std::size_t n = check.cause(static_cast<Cause>(k));
    if (n > 0) causes += (causes.empty() ? "" : ", ") + thousands(n) + " " + cause_name(static_cast<Cause>(k));
  }
  return s + (causes.empty() ? "" : ": " + causes) + ")";
}

Image disagreement_image(const CrossCheck& check, const RaySets& rays, const SceneGeometry& geometry,
                         const Accelerator& a, WorkerPool& pool) {
  Image image(check.width, check.height);
  pool.run([&] {
    tbb::parallel_for(std::size_t{0}, rays.camera.rays.size(), [&](std::size_t i) {
      const Ray& ray = rays.camera.rays[i];
      Hit hit;
      float grey = 0.02f;
      if (a.intersect(ray, hit)) {
        const SurfaceGeometry sg = surface(geometry.shapes[hit.shape], hit.prim, ray, PrimHit{hit.t, hit.uv});
        grey = 0.1f + 0.5f * std::fabs(dot(sg.ng, normalize(ray.dir)));
      }
      RGB c(grey, grey, grey);
      switch (check.pixel[rays.camera.pixel[i]]) {
        case Verdict::Agree: break;
        case Verdict::Tie: c = RGB(0.1f, 0.3f, 1.0f); break;
        case Verdict::Distance: c = RGB(1.0f, 0.85f, 0.0f); break;
        case Verdict::HitMiss: c = RGB(1.0f, 0.0f, 0.0f); break;
      }
      image.pixels[rays.camera.pixel[i]] = c;
    });
  });
  return image;
}

}  // namespace pt::bench
