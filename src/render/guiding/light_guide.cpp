#include "render/guiding/light_guide.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "geometry/shapes.h"
#include "render/guiding/prepass.h"
#include "render/materials/bsdf.h"
#include "render/render_scene.h"

namespace pt {

namespace {

constexpr int kMaxPrepassDepth = 6;  // bounces of a pre-pass path: deeper vertices add little that is new
constexpr uint64_t kPrepassKey = 0x6c69676874677569ULL;  // keeps the pre-pass apart from the render's numbers

struct Prepass {
  const RenderScene& scene;
  const EnvironmentBins& bins;
  const EnvironmentMap* map;
  int environment;  // its light index, or -1
  int max_depth;
  bool front_only;  // the learned visibility counts only tests in front of a reflecting surface
};

// Every infinite light tested from one vertex (the file comment of light_guide.h).
void test_lights(const Prepass& pp, const Intersection& isect, const Bsdf& bsdf, Vec3f wo, Rng& rng,
                 std::vector<LightGuide::Record>& out) {
  const LightSet& lights = pp.scene.lights;
  const int normal_class = LightGuide::normal_class(LightGuide::sky_normal(bsdf, wo));
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const bool env = static_cast<int>(i) == pp.environment;
    const int tests = env ? LightGuide::kEnvironmentTests : 1;
    for (int t = 0; t < tests; ++t) {
      LightGuide::Record r{isect.geo.p, static_cast<int>(i), -1, 0.0f, normal_class};
      LightSample ls;
      const Vec2f u(rng.next_float(), rng.next_float());
      if (sample_light(lights[i], isect.geo.p, u, ls) && ls.pdf > 0.0f && !ls.L.is_black()) {
        if (env) r.bin = pp.bins.bin_at(pp.map->direction_to_uv(ls.wi));
        const RGB f = bsdf.f(wo, ls.wi);
        // Where the render weighs the bins by the cosine (a reflecting BSDF, a
        // coarse plain part), a direction behind the surface tells nothing of
        // the bin's visibility: no test of the bin.
        if (env && f.is_black() && pp.front_only && normal_class >= 0) r.bin = -1;
        if (!f.is_black() && !pp.scene.occluded(spawn_ray(isect.geo, ls.wi))) {
          const float cos_i = std::fabs(dot(ls.wi, bsdf.shading_normal()));
          r.contribution = (f * ls.L).luminance() * cos_i / (ls.pdf * static_cast<float>(tests));
        }
      }
      if (!std::isfinite(r.contribution)) r.contribution = 0.0f;
      out.push_back(r);
    }
  }
}

// One pre-pass path through a random film position (BSDF sampling, Russian
// roulette after 3 bounces).
void trace_path(const Prepass& pp, Rng& rng, std::vector<LightGuide::Record>& out) {
  const RenderScene& scene = pp.scene;
  Ray ray = prepass_camera_ray(scene, rng);
  RGB beta(1.0f);
  for (int depth = 0; depth < pp.max_depth; ++depth) {
    Intersection isect;
    if (!scene.intersect(ray, isect)) return;
    const Vec3f wo = -ray.dir;
    const Bsdf bsdf(*isect.material, isect.geo, wo);
    if (bsdf.black()) return;
    if (!bsdf.delta_only()) test_lights(pp, isect, bsdf, wo, rng, out);
    BsdfSample bs;
    const float u_lobe = rng.next_float();
    if (!bsdf.sample(wo, u_lobe, Vec2f(rng.next_float(), rng.next_float()), bs)) return;
    beta *= bs.weight;
    if (beta.is_black()) return;
    if (depth >= 3) {
      const float survive = std::min(1.0f, beta.max_component());
      if (rng.next_float() >= survive) return;
      beta *= 1.0f / survive;
    }
    ray = spawn_ray(isect.geo, bs.wi);
  }
}

}  // namespace

LightGuide LightGuide::learn(const RenderScene& scene, WorkerPool& pool, int paths_per_pixel, int max_depth,
                             uint64_t seed, bool choose_light) {
  LightGuide guide(scene.lights);
  const LightSet& lights = scene.lights;
  if (paths_per_pixel <= 0 || max_depth <= 0 || lights.empty()) return guide;
  bool all_infinite = true;
  for (const Light& l : lights) all_infinite = all_infinite && std::visit([](const auto& k) { return k.infinite; }, l);
  const int env = lights.environment();
  if (env >= 0) {
    if (const auto* e = std::get_if<EnvironmentLight>(&lights[static_cast<std::size_t>(env)])) guide.map_ = e->map;
  }
  guide.guide_choice_ = choose_light && all_infinite && lights.needs_choice();
  if (guide.map_ == nullptr && !guide.guide_choice_) return guide;
  if (guide.map_ != nullptr) {
    guide.bins_ = EnvironmentBins(*guide.map_);
    guide.coarse_plain_ = guide.bins_.coarse_chi2() <= kMaxCoarseChi2;
  }
  if (guide.guide_choice_) {
    for (std::size_t i = 0; i < lights.size(); ++i)
      guide.plain_choice_.push_back(lights.pmf(Vec3f(), Vec3f(), static_cast<int>(i)));
  }
  const int64_t paths = std::min(kMaxPrepassPaths, int64_t{paths_per_pixel} * scene.width * scene.height);
  const Prepass pp{scene, guide.bins_, guide.map_, guide.map_ != nullptr ? env : -1,
                   std::min(max_depth, kMaxPrepassDepth), guide.coarse_plain_};
  std::vector<Record> records = run_prepass<Record>(
      pool, paths, seed, kPrepassKey, [&](Rng& rng, std::vector<Record>& out) { trace_path(pp, rng, out); });
  guide.tree_.build(records, kLeafRecords, [&](const Record* first, std::size_t count) {
    guide.leaves_.emplace_back();
    guide.learn_leaf(guide.leaves_.back(), first, count);
  });
  return guide;
}

// The choice: each light's share of the contributions. The environment: per
// bin, the fraction of the map's samples that arrived unoccluded, with
// kPriorTests pseudo-tests at the leaf's mean fraction (a bin without tests
// keeps that mean), times the bin's share of the map's importance.
void LightGuide::learn_leaf(Leaf& leaf, const Record* first, std::size_t count) const {
  if (count < static_cast<std::size_t>(kMinLeafRecords)) return;
  const std::size_t n = lights_->size();
  std::vector<double> per_light(n, 0.0);
  const std::size_t bins = map_ != nullptr ? static_cast<std::size_t>(bins_.size()) : 0;
  std::vector<float> tests(bins, 0.0f), seen(bins, 0.0f);
  double all_tests = 0.0, all_seen = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const Record& r = first[i];
    per_light[static_cast<std::size_t>(r.light)] += r.contribution;
    if (r.bin < 0) continue;
    const float visible = r.contribution > 0.0f ? 1.0f : 0.0f;
    tests[static_cast<std::size_t>(r.bin)] += 1.0f;
    seen[static_cast<std::size_t>(r.bin)] += visible;
    all_tests += 1.0;
    all_seen += visible;
  }
  double total = 0.0;
  for (double c : per_light) total += c;
  if (guide_choice_ && total > 0.0) {
    leaf.choice.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      leaf.choice[i] = kPlainChoice * plain_choice_[i] +
                       (1.0f - kPlainChoice) * static_cast<float>(per_light[i] / total);
  }
  if (!(all_seen > 0.0)) return;
  const float mean = static_cast<float>(all_seen / all_tests);
  std::vector<float> weight(bins);
  double sum = 0.0;
  for (std::size_t b = 0; b < bins; ++b) {
    weight[b] = bins_.share(static_cast<int>(b)) * (seen[b] + kPriorTests * mean) / (tests[b] + kPriorTests);
    sum += weight[b];
  }
  // A coarse plain part joins the mixture here: the bins' shares of the map's importance.
  if (coarse_plain_) {
    for (std::size_t b = 0; b < bins; ++b)
      weight[b] = kPlainEnvironment * bins_.share(static_cast<int>(b)) +
                  (1.0f - kPlainEnvironment) * static_cast<float>(weight[b] / sum);
  }
  leaf.environment = Distribution1D(weight);
  if (coarse_plain_) {  // the product with each normal class's cosine bounds (the file comment of light_guide.h)
    std::vector<int> of_class(kNormalClasses, 0);
    for (std::size_t i = 0; i < count; ++i)
      if (first[i].normal_class >= 0) ++of_class[static_cast<std::size_t>(first[i].normal_class)];
    leaf.by_normal.resize(kNormalClasses);
    std::vector<float> product(bins);
    for (int c = 0; c < kNormalClasses; ++c) {
      const Vec3f axis = class_direction(c);
      if (!(dot(axis, axis) > 0.0f) || of_class[static_cast<std::size_t>(c)] < kMinClassRecords) continue;
      for (std::size_t b = 0; b < bins; ++b)
        product[b] = weight[b] * (bins_.cosine_bound(static_cast<int>(b), axis, kClassChord) + kCosineFloor);
      leaf.by_normal[static_cast<std::size_t>(c)] = Distribution1D(product);
    }
  }
}

Vec3f LightGuide::sky_normal(const Bsdf& bsdf, Vec3f wo) {
  if (bsdf.transmits() || bsdf.delta_only()) return {};
  const Vec3f n = bsdf.shading_normal();
  return dot(n, wo) < 0.0f ? -n : n;
}

int LightGuide::normal_class(Vec3f n) {
  const float m = std::max({std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)});
  if (!(m > 0.0f)) return -1;
  const float t = kTan22_5 * m;
  const auto sign = [t](float v) { return v > t ? 2 : (v < -t ? 0 : 1); };
  return sign(n.x) * 9 + sign(n.y) * 3 + sign(n.z);
}

Vec3f LightGuide::class_direction(int c) {
  if (c < 0 || c >= kNormalClasses || c == 13) return {};
  const Vec3f d(static_cast<float>(c / 9 - 1), static_cast<float>(c / 3 % 3 - 1), static_cast<float>(c % 3 - 1));
  return normalize(d);
}

LightGuide::Site LightGuide::site(Vec3f p, Vec3f n) const {
  Site at{p, leaf(p)};
  if (at.leaf == nullptr || at.leaf->by_normal.empty()) return at;
  const int c = normal_class(n);
  if (c >= 0 && at.leaf->by_normal[static_cast<std::size_t>(c)].size() > 0)
    at.environment = &at.leaf->by_normal[static_cast<std::size_t>(c)];
  return at;
}

const LightGuide::Leaf* LightGuide::leaf(Vec3f p) const {
  if (tree_.empty()) return nullptr;
  return &leaves_[static_cast<std::size_t>(tree_.leaf(p))];
}

int LightGuide::choose(const Site& at, Vec3f n, float u, float& pmf) const {
  const Leaf* l = guide_choice_ ? at.leaf : nullptr;
  if (l == nullptr || l->choice.empty()) return lights_->choose(at.p, n, u, pmf);
  const std::size_t count = l->choice.size();
  float sum = 0.0f;
  for (std::size_t i = 0; i < count; ++i) {
    const float q = l->choice[i];
    if (q > 0.0f && (u < sum + q || i + 1 == count)) {
      pmf = q;
      return static_cast<int>(i);
    }
    sum += q;
  }
  pmf = 0.0f;  // not reached: the last light with a positive probability takes what rounding leaves
  return -1;
}

float LightGuide::pmf(const Site& at, Vec3f n, int light) const {
  const Leaf* l = guide_choice_ ? at.leaf : nullptr;
  if (l == nullptr || l->choice.empty()) return lights_->pmf(at.p, n, light);
  if (light < 0 || static_cast<std::size_t>(light) >= l->choice.size()) return 0.0f;
  return l->choice[static_cast<std::size_t>(light)];
}

// The mixture's density: the leaf's bin probability times the bin's density in
// image coordinates, per solid angle, plus (unless the plain part is coarse and
// already in the leaf's bins) the map's own; the map's alone where the leaf guides nothing.
float LightGuide::environment_pdf(const Site& at, Vec2f uv) const {
  const Leaf* l = at.leaf;
  if (l == nullptr || l->environment.size() == 0) return map_->pdf_at(uv);
  const float plain = coarse_plain_ ? 0.0f : map_->pdf_at(uv);
  const int b = bins_.bin_at(uv);
  const float sin_theta = std::sin(kPi * uv.y);
  if (!(sin_theta > 0.0f)) return kPlainEnvironment * plain;
  const float p_bin = (at.environment != nullptr ? *at.environment : l->environment).pmf(static_cast<std::size_t>(b));
  const float guided = p_bin * bins_.density(b, uv) / (2.0f * kPi * kPi * sin_theta);
  return coarse_plain_ ? guided : kPlainEnvironment * plain + (1.0f - kPlainEnvironment) * guided;
}

bool LightGuide::sample(int light, const Site& at, Vec2f u, LightSample& s) const {
  const Light& l = (*lights_)[static_cast<std::size_t>(light)];
  if (map_ == nullptr || light != lights_->environment()) return sample_light(l, at.p, u, s);
  const Leaf* lf = at.leaf;
  if (lf == nullptr || lf->environment.size() == 0) return sample_light(l, at.p, u, s);
  s.delta = false;
  s.infinite = true;
  // A fine plain part: one sample of the mixture, u.x choosing the component and reused, rescaled.
  float v = u.x;
  if (!coarse_plain_) {
    if (u.x < kPlainEnvironment)
      return map_->sample_direction(Vec2f(std::min(u.x / kPlainEnvironment, kOneMinusEpsilon), u.y), s.wi) &&
             finish_environment_sample(at, s);
    v = std::min((u.x - kPlainEnvironment) / (1.0f - kPlainEnvironment), kOneMinusEpsilon);
  }
  // The bin, and v's place inside the bin's step of the cdf as the first image coordinate's number.
  const Distribution1D& bins = at.environment != nullptr ? *at.environment : lf->environment;
  float density = 0.0f;
  std::size_t b = 0;
  const float x = bins.sample_continuous(v, &density, &b);
  const float w = std::clamp(x * static_cast<float>(bins.size()) - static_cast<float>(b), 0.0f, kOneMinusEpsilon);
  const Vec2f uv = bins_.sample(static_cast<int>(b), Vec2f(w, u.y));
  map_->prefetch(uv);  // the texel finish_environment_sample reads (through the direction, the same one but at a texel's edge)
  s.wi = map_->uv_to_direction(uv);
  return finish_environment_sample(at, s);
}

// Radiance and density from the sampled direction, as pdf() gives them to a BSDF-sampled ray.
bool LightGuide::finish_environment_sample(const Site& at, LightSample& s) const {
  const Vec2f uv = map_->direction_to_uv(s.wi);
  s.L = map_->radiance_at(uv);
  s.pdf = environment_pdf(at, uv);
  return s.pdf > 0.0f;
}

float LightGuide::pdf(int light, const Site& at, Vec3f wi, Vec3f q, Vec3f n) const {
  const Light& l = (*lights_)[static_cast<std::size_t>(light)];
  if (map_ == nullptr || light != lights_->environment()) return light_pdf(l, at.p, wi, q, n);
  return environment_pdf(at, map_->direction_to_uv(wi));
}

}  // namespace pt
