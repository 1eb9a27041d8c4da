#include "render/guiding/path_guide.h"

#include <algorithm>
#include <cmath>

#include "geometry/shapes.h"
#include "render/materials/bsdf.h"
#include "render/render_scene.h"

namespace pt {

namespace {

constexpr uint64_t kPrepassKey = 0x7061746867756964ULL;  // keeps the pre-pass apart from the render's numbers

// A non-delta vertex of a pre-pass path, waiting for what its bounce brings back.
struct Pending {
  Vec3f p;
  int bin;
  int normal_class;
  float pdf;         // the bounce direction's density
  RGB beta_after;    // the path's throughput after the bounce
  RGB incident;      // the radiance found along the bounce so far
};

float ratio(float a, float b) { return b > 0.0f ? a / b : 0.0f; }

// Adds `found` (a contribution to the camera, throughput included) to every pending vertex's incident radiance.
void credit(std::vector<Pending>& pending, RGB found) {
  if (found.is_black()) return;
  for (Pending& v : pending) {
    v.incident += RGB(ratio(found.r, v.beta_after.r), ratio(found.g, v.beta_after.g),
                      ratio(found.b, v.beta_after.b));
  }
}

// Next-event estimation with LightSet's plain choice, no MIS (the file comment of path_guide.h).
RGB next_event(const RenderScene& scene, const Intersection& isect, const Bsdf& bsdf, Vec3f wo, Rng& rng) {
  const LightSet& lights = scene.lights;
  if (lights.empty()) return {};
  float pmf = 0.0f;
  const int index = lights.choose(isect.geo.p, isect.geo.ng, rng.next_float(), pmf);
  if (index < 0 || !(pmf > 0.0f)) return {};
  LightSample ls;
  if (!sample_light(lights[static_cast<std::size_t>(index)], isect.geo.p, Vec2f(rng.next_float(), rng.next_float()),
                    ls) ||
      !(ls.pdf > 0.0f) || ls.L.is_black())
    return {};
  const RGB f = bsdf.f(wo, ls.wi);
  if (f.is_black() || scene.occluded(light_shadow_ray(isect.geo, ls))) return {};
  const float cos_i = std::fabs(dot(ls.wi, bsdf.shading_normal()));
  return f * ls.L * (cos_i / (pmf * ls.pdf));
}

// One pre-pass path (Russian roulette after 3 bounces); its non-delta vertices' records go to `out`.
void trace_path(const RenderScene& scene, int max_depth, Rng& rng, std::vector<PathGuide::Record>& out) {
  std::vector<Pending> pending;
  Ray ray = prepass_camera_ray(scene, rng);
  RGB beta(1.0f);
  bool specular = false;  // the last bounce was a delta one: emission found now counts
  for (int depth = 0;; ++depth) {
    Intersection isect;
    if (!scene.intersect(ray, isect)) {
      if (specular) credit(pending, beta * scene.escaped_radiance(ray.dir));
      break;
    }
    const Vec3f wo = -ray.dir;
    if (specular && isect.material->emits())
      credit(pending, beta * isect.material->emitted(isect.geo.ng, wo, tex_coord(isect.geo)));
    if (depth >= max_depth) break;
    const Bsdf bsdf(*isect.material, isect.geo, wo);
    if (bsdf.black()) break;
    if (!bsdf.delta_only()) credit(pending, beta * next_event(scene, isect, bsdf, wo, rng));
    BsdfSample bs;
    const float u_lobe = rng.next_float();
    if (!bsdf.sample(wo, u_lobe, Vec2f(rng.next_float(), rng.next_float()), bs)) break;
    beta *= bs.weight;
    if (beta.is_black()) break;
    specular = bs.delta;
    if (!bs.delta) pending.push_back({isect.geo.p, DirectionGrid::bin(bs.wi), PathGuide::normal_class(bsdf.shading_normal()),
                                     bs.pdf, beta, RGB()});
    if (depth >= 3) {
      const float survive = std::min(1.0f, beta.max_component());
      if (rng.next_float() >= survive) break;
      beta *= 1.0f / survive;
    }
    ray = spawn_ray(isect.geo, bs.wi);
  }
  for (const Pending& v : pending) {
    float value = v.incident.luminance();
    if (!std::isfinite(value) || value < 0.0f) value = 0.0f;
    out.push_back({v.p, v.bin, v.normal_class, value});
  }
}

}  // namespace

int DirectionGrid::bin(Vec3f w) {
  const int row = std::clamp(static_cast<int>((w.z + 1.0f) * 0.5f * kRows), 0, kRows - 1);
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  const int column = std::clamp(static_cast<int>(phi * (kColumns / (2.0f * kPi))), 0, kColumns - 1);
  return row * kColumns + column;
}

Vec3f DirectionGrid::sample(int b, Vec2f u) {
  const int row = b / kColumns, column = b % kColumns;
  const float z = std::clamp(-1.0f + 2.0f * (static_cast<float>(row) + u.y) / kRows, -1.0f, 1.0f);
  const float phi = 2.0f * kPi * (static_cast<float>(column) + u.x) / kColumns;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

namespace {
Vec3f mirror(Vec3f w, Vec3f n) { return w - n * (2.0f * dot(w, n)); }
}  // namespace

Vec3f PathGuide::sample(const Leaf& leaf, Vec2f u, Vec3f n, float& pdf) {
  // The bin from u.x, and u.x's place inside the bin's step of the cdf, reused.
  float density = 0.0f;
  std::size_t b = 0;
  const float x = leaf.bins.sample_continuous(u.x, &density, &b);
  const float w = std::clamp(x * static_cast<float>(DirectionGrid::kBins) - static_cast<float>(b), 0.0f,
                             kOneMinusEpsilon);
  Vec3f dir = DirectionGrid::sample(static_cast<int>(b), Vec2f(w, u.y));
  if (dot(dir, n) < 0.0f) dir = mirror(dir, n);
  pdf = PathGuide::pdf(leaf, dir, n);
  return dir;
}

float PathGuide::pdf(const Leaf& leaf, Vec3f w, Vec3f n) {
  const auto at = [&](Vec3f d) {
    return leaf.bins.pmf(static_cast<std::size_t>(DirectionGrid::bin(d))) * DirectionGrid::kBinDensity;
  };
  if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) return at(w);
  const float c = dot(w, n);
  if (c < 0.0f) return 0.0f;
  return at(w) + at(mirror(w, n));
}

bool PathGuide::sample_bounce(const Bsdf& bsdf, const Leaf* region, Vec3f wo, float u_lobe, Vec2f u,
                              BsdfSample& s) {
  if (region == nullptr) return bsdf.sample(wo, u_lobe, u, s);
  const float a = kGuided;
  const Vec3f n = fold_normal(bsdf);
  if (u.x < a) {
    float guide_pdf = 0.0f;
    s.wi = sample(*region, Vec2f(std::min(u.x / a, kOneMinusEpsilon), u.y), n, guide_pdf);
    s.pdf = a * guide_pdf + (1.0f - a) * bsdf.pdf(wo, s.wi);
    const RGB f = bsdf.f(wo, s.wi);
    if (f.is_black() || !(s.pdf > 0.0f)) return false;
    s.weight = f * (std::fabs(dot(s.wi, bsdf.shading_normal())) / s.pdf);
    s.delta = false;
    s.eta2 = 1.0f;
    return true;
  }
  if (!bsdf.sample(wo, u_lobe, Vec2f(std::min((u.x - a) / (1.0f - a), kOneMinusEpsilon), u.y), s)) return false;
  if (s.delta) {
    s.weight *= 1.0f / (1.0f - a);
    s.pdf *= 1.0f - a;
    return true;
  }
  const float mixed = a * pdf(*region, s.wi, n) + (1.0f - a) * s.pdf;
  s.weight *= s.pdf / mixed;
  s.pdf = mixed;
  return true;
}

PathGuide PathGuide::learn(const RenderScene& scene, WorkerPool& pool, int paths_per_pixel, int max_depth,
                           uint64_t seed) {
  PathGuide guide;
  if (paths_per_pixel <= 0 || max_depth <= 0) return guide;
  const int64_t paths = std::min(kMaxPrepassPaths, int64_t{paths_per_pixel} * scene.width * scene.height);
  const int depth = std::min(max_depth, kMaxPrepassDepth);
  std::vector<Record> records = run_prepass<Record>(
      pool, paths, seed, kPrepassKey, [&](Rng& rng, std::vector<Record>& out) { trace_path(scene, depth, rng, out); });
  guide.tree_.build(records, kLeafRecords, [&](const Record* first, std::size_t count) {
    for (int c = 0; c < kNormalClasses; ++c) {
      guide.leaves_.emplace_back();
      guide.learn_leaf(guide.leaves_.back(), first, count, c);
    }
  });
  return guide;
}

// Each bin's share of the leaf's values, (1 - kPriorShare) of the mass; the
// rest evenly over every bin.
void PathGuide::learn_leaf(Leaf& leaf, const Record* first, std::size_t count, int normal_class) const {
  std::vector<double> sum(DirectionGrid::kBins, 0.0);
  double total = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (first[i].normal_class != normal_class) continue;
    sum[static_cast<std::size_t>(first[i].bin)] += first[i].value;
    total += first[i].value;
    ++n;
  }
  if (n < static_cast<std::size_t>(kMinLeafRecords)) return;
  if (!(total > 0.0) || !std::isfinite(total)) return;
  constexpr double prior = kPriorShare;
  std::vector<float> weight(DirectionGrid::kBins);
  const double even = prior / DirectionGrid::kBins;
  for (std::size_t b = 0; b < weight.size(); ++b)
    weight[b] = static_cast<float>((1.0 - prior) * sum[b] / total + even);
  leaf.bins = Distribution1D(weight);
}

}  // namespace pt
