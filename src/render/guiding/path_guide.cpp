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
  Vec2f s;           // the bounce direction in DirectionTree's square
  int normal_class;
  float weight;      // |cos| at the vertex / the bounce direction's density
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

// One pre-pass path (Russian roulette after 3 bounces), its bounces sampled
// with `guide` (the last iteration's; inactive: the BSDF's); its non-delta
// vertices' records go to `out`.
void trace_path(const RenderScene& scene, const PathGuide& guide, int max_depth, Rng& rng,
                std::vector<PathGuide::Record>& out) {
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
    const Vec3f n = bsdf.shading_normal();
    const PathGuide::Leaf* region = bsdf.delta_only() ? nullptr : guide.leaf(isect.geo.p, n);
    if (!PathGuide::sample_bounce(bsdf, region, wo, u_lobe, Vec2f(rng.next_float(), rng.next_float()), bs)) break;
    beta *= bs.weight;
    if (beta.is_black()) break;
    specular = bs.delta;
    if (!bs.delta)
      pending.push_back({isect.geo.p, DirectionTree::to_square(bs.wi), PathGuide::normal_class(n),
                         ratio(std::fabs(dot(bs.wi, n)), bs.pdf), beta, RGB()});
    if (depth >= 3) {
      const float survive = std::min(1.0f, beta.max_component());
      if (rng.next_float() >= survive) break;
      beta *= 1.0f / survive;
    }
    ray = spawn_ray(isect.geo, bs.wi);
  }
  for (const Pending& v : pending) {
    float value = v.incident.luminance() * v.weight;
    if (!std::isfinite(value) || value < 0.0f) value = 0.0f;
    out.push_back({v.p, v.s, v.normal_class, value});
  }
}

}  // namespace

Vec2f DirectionTree::to_square(Vec3f w) {
  float phi = std::atan2(w.y, w.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return {std::clamp((w.z + 1.0f) * 0.5f, 0.0f, kOneMinusEpsilon),
          std::clamp(phi * (1.0f / (2.0f * kPi)), 0.0f, kOneMinusEpsilon)};
}

Vec3f DirectionTree::from_square(Vec2f s) {
  const float z = std::clamp(2.0f * s.x - 1.0f, -1.0f, 1.0f);
  const float phi = 2.0f * kPi * s.y;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

void DirectionTree::build(Point* first, std::size_t count, float split_share, std::size_t min_points) {
  nodes_.clear();
  double total = 0.0;
  for (std::size_t i = 0; i < count; ++i) total += first[i].value;
  if (!(total > 0.0) || !std::isfinite(total)) return;
  build_node(first, count, total, 1.0f, 0, split_share, min_points);
}

// The node for the square cell holding points [first, first + count) (in the
// cell's own coordinates, [0, 1)^2), of `area` (a share of the square).
int DirectionTree::build_node(Point* first, std::size_t count, double total, float area, int depth,
                              float split_share, std::size_t min_points) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  // The points by quadrant, and each moved into its quadrant's coordinates.
  const auto quadrant = [](const Point& q) { return (q.s.x >= 0.5f ? 1 : 0) + (q.s.y >= 0.5f ? 2 : 0); };
  std::size_t begin[5] = {0, 0, 0, 0, count};
  Point* const last = first + count;
  Point* at = first;
  for (int q = 0; q < 3; ++q) {
    at = std::partition(at, last, [&](const Point& x) { return quadrant(x) == q; });
    begin[q + 1] = static_cast<std::size_t>(at - first);
  }
  double value[4] = {0.0, 0.0, 0.0, 0.0};
  for (int q = 0; q < 4; ++q) {
    for (std::size_t i = begin[q]; i < begin[q + 1]; ++i) {
      Point& x = first[i];
      value[q] += x.value;
      x.s = Vec2f(std::min(2.0f * x.s.x - static_cast<float>(q & 1), kOneMinusEpsilon),
                  std::min(2.0f * x.s.y - static_cast<float>(q >> 1), kOneMinusEpsilon));
    }
  }
  const double prior = kPriorShare;
  double mass[4], sum = 0.0;
  for (int q = 0; q < 4; ++q) sum += mass[q] = (1.0 - prior) * value[q] / total + prior * 0.25 * area;
  for (int q = 0; q < 4; ++q) nodes_[static_cast<std::size_t>(index)].p[q] = static_cast<float>(mass[q] / sum);
  for (int q = 0; q < 4; ++q) {
    const std::size_t n = begin[q + 1] - begin[q];
    if (depth + 1 < kMaxDepth && n >= min_points && value[q] > split_share * total) {
      const int child =
          build_node(first + begin[q], n, total, 0.25f * area, depth + 1, split_share, min_points);
      nodes_[static_cast<std::size_t>(index)].child[q] = child;
    }
  }
  return index;
}

float DirectionTree::pdf(Vec3f w) const {
  if (nodes_.empty()) return 0.0f;
  Vec2f s = to_square(w);
  float density = 1.0f;
  for (const Node* node = &nodes_[0];;) {
    const int x = s.x >= 0.5f ? 1 : 0, y = s.y >= 0.5f ? 1 : 0, q = x + 2 * y;
    density *= 4.0f * node->p[q];
    if (node->child[q] == 0) break;
    node = &nodes_[static_cast<std::size_t>(node->child[q])];
    s = Vec2f(std::min(2.0f * s.x - static_cast<float>(x), kOneMinusEpsilon),
              std::min(2.0f * s.y - static_cast<float>(y), kOneMinusEpsilon));
  }
  return density * (1.0f / (4.0f * kPi));
}

namespace {
// Chooses the upper half (1) with probability `upper` of [0, 1), rescaling u into it.
int choose_half(float& u, float upper) {
  const float lower = 1.0f - upper;
  if (u < lower) {
    u = std::min(u / lower, kOneMinusEpsilon);
    return 0;
  }
  u = std::min((u - lower) / upper, kOneMinusEpsilon);
  return 1;
}
}  // namespace

Vec3f DirectionTree::sample(Vec2f u, float& pdf) const {
  if (nodes_.empty()) {
    pdf = 1.0f / (4.0f * kPi);
    return from_square(u);
  }
  Vec2f origin(0.0f, 0.0f);
  float size = 1.0f;
  for (const Node* node = &nodes_[0];;) {
    const float* p = node->p;
    const int x = choose_half(u.x, p[1] + p[3]);
    const int y = choose_half(u.y, p[x + 2] / (p[x] + p[x + 2]));
    const int q = x + 2 * y;
    size *= 0.5f;
    origin = Vec2f(origin.x + static_cast<float>(x) * size, origin.y + static_cast<float>(y) * size);
    if (node->child[q] == 0) break;
    node = &nodes_[static_cast<std::size_t>(node->child[q])];
  }
  const Vec3f w = from_square(Vec2f(std::min(origin.x + u.x * size, kOneMinusEpsilon),
                                    std::min(origin.y + u.y * size, kOneMinusEpsilon)));
  pdf = this->pdf(w);
  return w;
}

namespace {
Vec3f mirror(Vec3f w, Vec3f n) { return w - n * (2.0f * dot(w, n)); }
}  // namespace

Vec3f PathGuide::sample(const Leaf& leaf, Vec2f u, Vec3f n, float& pdf) {
  Vec3f dir = leaf.directions.sample(u, pdf);
  if (dot(dir, n) < 0.0f) dir = mirror(dir, n);
  pdf = PathGuide::pdf(leaf, dir, n);
  return dir;
}

float PathGuide::pdf(const Leaf& leaf, Vec3f w, Vec3f n) {
  if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) return leaf.directions.pdf(w);
  const float c = dot(w, n);
  if (c < 0.0f) return 0.0f;
  return leaf.directions.pdf(w) + leaf.directions.pdf(mirror(w, n));
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
  // Iteration k traces paths x 2^k / (2^kIterations - 1) paths with the guide
  // learned from the records of the iterations before it.
  std::vector<Record> records;
  const int64_t parts = (int64_t{1} << kIterations) - 1;
  int64_t first_path = 0;
  for (int k = 0; k < kIterations; ++k) {
    const int64_t end = k + 1 == kIterations ? paths : paths * ((int64_t{1} << (k + 1)) - 1) / parts;
    if (end <= first_path) continue;
    std::vector<Record> more = run_prepass<Record>(
        pool, end - first_path, hash_keys(seed, static_cast<uint64_t>(first_path)), kPrepassKey,
        [&](Rng& rng, std::vector<Record>& out) { trace_path(scene, guide, depth, rng, out); });
    records.insert(records.end(), more.begin(), more.end());
    first_path = end;
    guide.build(records);
  }
  return guide;
}

void PathGuide::build(std::vector<Record>& records) {
  tree_ = SpatialTree();
  leaves_.clear();
  tree_.build(records, kLeafRecords, [&](const Record* first, std::size_t count) {
    for (int c = 0; c < kNormalClasses; ++c) {
      leaves_.emplace_back();
      learn_leaf(leaves_.back(), first, count, c);
    }
  });
}

// The records of one normal class in the leaf, as a direction tree.
void PathGuide::learn_leaf(Leaf& leaf, const Record* first, std::size_t count, int normal_class) const {
  std::vector<DirectionTree::Point> points;
  for (std::size_t i = 0; i < count; ++i)
    if (first[i].normal_class == normal_class) points.push_back({first[i].s, first[i].value});
  if (points.size() < kMinLeafRecords) return;
  leaf.directions.build(points.data(), points.size(), kSplitShare, kMinCellRecords);
}

}  // namespace pt
