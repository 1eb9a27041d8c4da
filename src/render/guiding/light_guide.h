// Light guiding for the path integrator (docs/path-tracing.md, "Light
// guiding"): next-event estimation that has learned, per region of space,
// which lights reach it and from which directions the environment does.
//
// Before the render (render.light_guiding pre-pass paths per pixel; 0 = off)
// a fixed pre-pass traces camera paths (BSDF-sampled, independent of the
// render's sampler: a function of the seed alone) and at each vertex tests
// every infinite light: a shadow ray to each directional light, and
// kEnvironmentTests shadow rays to environment-map samples (paths of at most
// 6 bounces). Each test records
// its vertex, the light, the environment bin (environment_bins.h) and its
// contribution (luminance of f L cos / pdf, 0 if occluded). A binary tree
// over space splits the records' bounds at the middle of the longest axis
// until a leaf holds at most kLeafRecords; then, per leaf:
//  - the environment is sampled from the mixture kPlainEnvironment x the map's
//    own distribution (for a smooth sky, kMaxCoarseChi2: the bins' coarse
//    version of it, folded into the leaf's distribution over bins, so that a
//    sample and a density read no table of the map's size) +
//    (1 - kPlainEnvironment) x a distribution over bins in
//    proportion to the bin's share of the map's importance times the fraction
//    of the leaf's tests that arrived unoccluded there (within a bin, by the
//    bin's coarse importance grid, environment_bins.h): directions the leaf's
//    points see through an opening;
//  - at a vertex whose sky cannot come from behind (a BSDF that does not
//    transmit: site(p, n)), that distribution over bins (plain part included)
//    times, per bin, an upper bound of the cosine between the bin's directions
//    and the normal's class (the nearest of 26 directions: the cube's faces,
//    edges and corners), plus kCosineFloor (EnvironmentBins::cosine_bound):
//    the samples that a leaf mixing floors and walls spent behind the surface
//    (about 40% on Sponza) go in front of it. One table per leaf and class,
//    made with the leaf for the classes of at least kMinClassRecords of its
//    records (a vertex of another class samples the leaf's own); only for the
//    coarse plain part (a smooth sky);
//  - when every light is infinite (sun and sky), the light is chosen with
//    probability kPlainChoice x LightSet's + (1 - kPlainChoice) x the leaf's
//    share of the learned contributions: shadowed regions sample the sky.
// The learned data is frozen before the render, so a sample still depends
// only on (seed, pixel, index) (bit-identical for any thread count), and the
// mixtures keep every density positive wherever the plain one is, so the
// estimator stays unbiased. An inactive guide (no environment map and fewer
// than two infinite lights, or guiding off) is LightSet's choice and the
// lights' own sampling, bit for bit.
#pragma once

#include <cstdint>
#include <vector>

#include "core/sampling.h"
#include "render/guiding/environment_bins.h"
#include "render/guiding/prepass.h"
#include "render/lights/light_set.h"

namespace pt {

class Bsdf;
class WorkerPool;
struct RenderScene;

class LightGuide {
 public:
  static constexpr int kEnvironmentTests = 1;   // environment shadow rays per pre-pass vertex
  static constexpr int kLeafRecords = 2048;     // a leaf's most records
  static constexpr int kMinLeafRecords = 64;    // fewer: the leaf guides nothing
  static constexpr float kPlainEnvironment = 0.25f;
  // The plain part is drawn from the bins' coarse grid, not the map's own
  // tables, where that adds at most this relative variance to an unoccluded
  // estimate of the sky (EnvironmentBins::coarse_chi2): a smooth sky.
  static constexpr float kMaxCoarseChi2 = 0.05f;
  static constexpr float kPlainChoice = 0.1f;
  static constexpr float kPriorTests = 2.0f;  // pseudo-tests per bin at the leaf's mean visibility
  static constexpr int64_t kMaxPrepassPaths = int64_t{1} << 18;
  // Added to each bin's cosine bound (the file comment): every bin keeps a
  // positive density for every class, so the estimator stays unbiased
  // whatever normal a vertex gives.
  static constexpr float kCosineFloor = 0.02f;
  static constexpr int kNormalClasses = 27;  // 3^3 sign patterns; the zero one unused
  static constexpr int kMinClassRecords = 16;  // a leaf's records of a class for its table
  static constexpr float kTan22_5 = 0.41421356f;
  // A unit normal is within this chord of its class's direction (at most
  // 0.523, about 30 degrees: LightGuide.NormalClassesAreWithinTheirChord).
  static constexpr float kClassChord = 0.53f;

  // The inactive guide.
  explicit LightGuide(const LightSet& lights) : lights_(&lights) {}
  // Learns from a pre-pass of `paths_per_pixel` x width x height camera paths
  // (at most kMaxPrepassPaths) of at most `max_depth` bounces, run in `pool`.
  // `choose_light`: whether the integrator chooses one light per vertex (it
  // does not where it estimates each of a few infinite lights,
  // LightSet::each_lights): only then is a choice among them learned.
  static LightGuide learn(const RenderScene& scene, WorkerPool& pool, int paths_per_pixel, int max_depth,
                          uint64_t seed, bool choose_light = true);

  bool active() const { return !tree_.empty(); }
  int leaves() const { return static_cast<int>(leaves_.size()); }

  struct Leaf {
    std::vector<float> choice;  // per light: its probability (empty: LightSet's)
    Distribution1D environment;  // over bins (empty: the map's own)
    // Per normal class (normal_class): the environment's distribution times
    // the class's cosine bounds (empty: no product in this leaf).
    std::vector<Distribution1D> by_normal;
  };
  // A shading point, its leaf and the leaf's distribution over bins there,
  // looked up once for the calls below.
  struct Site {
    Vec3f p;
    const Leaf* leaf = nullptr;
    const Distribution1D* environment = nullptr;  // the sky's bins at this point (null: the leaf's own)
  };
  Site site(Vec3f p) const { return {p, leaf(p)}; }
  // `n`: the unit normal on the side the sky may light (a reflecting BSDF's
  // shading normal towards wo); a zero vector: no product with the cosine.
  Site site(Vec3f p, Vec3f n) const;
  // The normal the sky's bins are weighed by at a vertex with this BSDF seen
  // from wo: the shading normal on wo's side where the BSDF only reflects, a
  // zero vector (no product) where light may come through or it is all delta.
  static Vec3f sky_normal(const Bsdf& bsdf, Vec3f wo);
  // The class of a normal (the nearest of the 26 directions, by the signs of
  // its components larger than tan(22.5 degrees) x the largest), or -1 for the zero vector.
  static int normal_class(Vec3f n);
  // Its central direction (unit).
  static Vec3f class_direction(int c);

  // LightSet::choose and pmf, guided.
  int choose(const Site& at, Vec3f n, float u, float& pmf) const;
  float pmf(const Site& at, Vec3f n, int light) const;
  // sample_light and light_pdf for the light with index `light`, guided.
  bool sample(int light, const Site& at, Vec2f u, LightSample& s) const;
  float pdf(int light, const Site& at, Vec3f wi, Vec3f q, Vec3f n) const;
  // The same, looking the point up.
  int choose(Vec3f p, Vec3f n, float u, float& pmf) const { return choose(site(p), n, u, pmf); }
  float pmf(Vec3f p, Vec3f n, int light) const { return pmf(site(p), n, light); }
  bool sample(int light, Vec3f p, Vec2f u, LightSample& s) const { return sample(light, site(p), u, s); }
  float pdf(int light, Vec3f p, Vec3f wi, Vec3f q, Vec3f n) const { return pdf(light, site(p), wi, q, n); }

  struct Record {
    Vec3f p;
    int light;
    int bin;  // the environment's bin, or -1
    float contribution;
    int normal_class = -1;  // normal_class(sky_normal(...)) of the vertex, or -1
  };

 private:
  void learn_leaf(Leaf& leaf, const Record* first, std::size_t count) const;
  const Leaf* leaf(Vec3f p) const;
  float environment_pdf(const Site& at, Vec2f uv) const;
  bool finish_environment_sample(const Site& at, LightSample& s) const;


  const LightSet* lights_;
  const EnvironmentMap* map_ = nullptr;
  EnvironmentBins bins_;
  bool coarse_plain_ = false;  // the plain part from the bins (bins_.coarse_chi2() <= kMaxCoarseChi2)
  bool guide_choice_ = false;
  std::vector<float> plain_choice_;  // per light: LightSet's probability (all lights infinite)
  SpatialTree tree_;
  std::vector<Leaf> leaves_;
};

}  // namespace pt
