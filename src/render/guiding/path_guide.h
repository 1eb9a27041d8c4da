// Path guiding for the path integrator (docs/path-tracing.md, "Path
// guiding"): bounce directions sampled towards where, in this region of space,
// the indirect light comes from.
//
// Before the render (render.path_guiding pre-pass paths per pixel; 0 = off) a
// fixed pre-pass traces camera paths with BSDF sampling and next-event
// estimation (LightSet's plain choice and sampling, no MIS: emission found by
// a BSDF ray counts only after a delta bounce, which no shadow ray can
// replace). Each non-delta vertex records its position, its shading normal's
// class (main axis and side), the bin of its bounce direction on an
// equal-area grid over the sphere (DirectionGrid) and the luminance of the
// radiance the rest of the path brought back along that direction: light
// arriving through other surfaces (and through delta bounces), which
// next-event estimation does not sample. The directions were BSDF-sampled, so
// a bin's sum estimates that radiance weighted by the BSDF's density (for a
// diffuse surface L cos: the product a bounce should follow). A midpoint tree
// over space (SpatialTree) splits the records until a leaf holds at most
// kLeafRecords; per leaf and normal class with at least kMinLeafRecords, the
// distribution over bins is the records' sums, with kPriorShare of the mass
// spread evenly (a bin without records is not left at zero).
//
// The integrator samples a bounce from the one-sample mixture kGuided x the
// distribution (uniform within a bin; for a reflective BSDF, a direction
// below the shading normal is mirrored above it, the density folded) +
// (1 - kGuided) x the BSDF, with density kGuided x guide + (1 - kGuided) x
// bsdf, used everywhere the BSDF's density was (the estimator's weight and
// MIS with next-event estimation), so the estimate stays unbiased: the
// mixture's density is positive wherever the BSDF's is. The learned data is
// frozen before the render, a function of the seed alone, so the image is
// bit-identical for any thread count. Where nothing was learned the density
// is the BSDF's and the samples are Bsdf::sample's.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/sampling.h"
#include "render/guiding/prepass.h"
#include "render/materials/bsdf.h"

namespace pt {

class WorkerPool;
struct RenderScene;

// Directions on the unit sphere in bins of equal solid angle: kRows bands of
// equal height in z = cos theta, kColumns sectors of equal width in phi.
struct DirectionGrid {
  static constexpr int kRows = 4;
  static constexpr int kColumns = 8;
  static constexpr int kBins = kRows * kColumns;
  static int bin(Vec3f w);
  // A direction in bin b, uniformly over the bin's solid angle.
  static Vec3f sample(int b, Vec2f u);
  // The density per solid angle of a direction uniform over one bin.
  static constexpr float kBinDensity = static_cast<float>(kBins) / (4.0f * kPi);
};

class PathGuide {
 public:
  static constexpr float kGuided = 0.3f;        // the mixture's share of guided bounces
  static constexpr std::size_t kLeafRecords = 1024;  // a region's most records
  static constexpr std::size_t kMinLeafRecords = 128;  // fewer (of one normal class): nothing guided
  static constexpr float kPriorShare = 0.2f;    // of a distribution, spread evenly over the bins
  static constexpr int kMaxPrepassDepth = 8;    // bounces of a pre-pass path
  static constexpr int64_t kMaxPrepassPaths = int64_t{1} << 18;

  PathGuide() = default;  // inactive
  // Learns from a pre-pass of `paths_per_pixel` x width x height camera paths
  // (at most kMaxPrepassPaths) of at most min(max_depth, kMaxPrepassDepth) bounces.
  static PathGuide learn(const RenderScene& scene, WorkerPool& pool, int paths_per_pixel, int max_depth,
                         uint64_t seed);

  bool active() const { return !tree_.empty(); }
  int leaves() const { return static_cast<int>(leaves_.size()); }

  // A region's learned distribution over DirectionGrid's bins for one normal class (empty: none).
  struct Leaf {
    Distribution1D bins;
  };
  // The leaf holding p, or nullptr where nothing is guided.
  // The distribution for a point p whose surface has normal n (a region's
  // records are split by the normal's main axis and side: a floor and the
  // wall beside it see their light from different hemispheres), or nullptr
  // where nothing is guided.
  const Leaf* leaf(Vec3f p, Vec3f n) const {
    if (tree_.empty()) return nullptr;
    const Leaf* l = &leaves_[static_cast<std::size_t>(tree_.leaf(p) * kNormalClasses + normal_class(n))];
    return l->bins.size() > 0 ? l : nullptr;
  }
  static constexpr int kNormalClasses = 6;
  static int normal_class(Vec3f n) {
    const float ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
    if (ax >= ay && ax >= az) return n.x < 0.0f ? 1 : 0;
    if (ay >= az) return n.y < 0.0f ? 3 : 2;
    return n.z < 0.0f ? 5 : 4;
  }
  // A direction from the leaf's distribution and its density per solid
  // angle. With a normal n (not zero: a reflective BSDF's shading normal), a
  // direction below it is mirrored above it: the density over n's hemisphere
  // is then p(w) + p(mirror(w)), 0 below (folded).
  static Vec3f sample(const Leaf& leaf, Vec2f u, Vec3f n, float& pdf);
  static float pdf(const Leaf& leaf, Vec3f w, Vec3f n);

  // The density of a bounce towards wi from a vertex in `region`: the BSDF's
  // (bsdf.pdf), or the mixture's where the region guides (not null).
  static float bounce_pdf(const Bsdf& bsdf, const Leaf* region, Vec3f wo, Vec3f wi) {
    const float p = bsdf.pdf(wo, wi);
    return region == nullptr ? p : kGuided * pdf(*region, wi, fold_normal(bsdf)) + (1.0f - kGuided) * p;
  }
  // Bsdf::sample, or one sample of the mixture where `region` guides: u.x
  // chooses the component and is reused, rescaled (the same sample
  // dimensions either way). s.pdf is bounce_pdf (a delta lobe: its
  // probability times 1 - kGuided) and s.weight f |cos| / s.pdf.
  static bool sample_bounce(const Bsdf& bsdf, const Leaf* region, Vec3f wo, float u_lobe, Vec2f u, BsdfSample& s);
  // The normal the guide's directions are folded about (zero: none).
  static Vec3f fold_normal(const Bsdf& bsdf) { return bsdf.transmits() ? Vec3f() : bsdf.shading_normal(); }

  struct Record {
    Vec3f p;
    int bin;
    int normal_class;  // of the vertex's shading normal
    float value;  // luminance of the incident radiance / the direction's density
  };

 private:
  void learn_leaf(Leaf& leaf, const Record* first, std::size_t count, int normal_class) const;

  SpatialTree tree_;
  std::vector<Leaf> leaves_;
};

}  // namespace pt
