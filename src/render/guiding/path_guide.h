// Path guiding for the path integrator (docs/path-tracing.md, "Path
// guiding"): bounce directions sampled towards where, in this region of space,
// the indirect light comes from.
//
// Before the render (render.path_guiding pre-pass paths per pixel; 0 = off) a
// fixed pre-pass traces camera paths with next-event estimation (LightSet's
// plain choice and sampling, no MIS: emission found by a BSDF ray counts only
// after a delta bounce, which no shadow ray can replace), in kIterations
// iterations of doubling size, each sampling its bounces from the mixture with
// the guide learned from the iterations before it (the first: the BSDF
// alone). Each non-delta vertex records its position, its shading normal's
// class (main axis and side), its bounce direction and the luminance of the
// radiance the rest of the path brought back along that direction (light
// arriving through other surfaces and delta bounces, which next-event
// estimation does not sample) times |cos| over the direction's density: an
// estimate of the incident indirect light times the cosine, whichever mixture
// sampled it, so all iterations' records are learned from together. A
// midpoint tree over space (SpatialTree) splits the records until a leaf
// holds at most kLeafRecords; per leaf and normal class with at least
// kMinLeafRecords, a DirectionTree of the records: the distribution a diffuse
// bounce should follow (L cos).
//
// The integrator samples a bounce from the one-sample mixture kGuided x the
// tree's distribution (for a reflective BSDF, a direction below the shading
// normal is mirrored above it, the density folded) + (1 - kGuided) x the
// BSDF, with density kGuided x guide + (1 - kGuided) x bsdf, used everywhere
// the BSDF's density was (the estimator's weight and MIS with next-event
// estimation), so the estimate stays unbiased: the mixture's density is
// positive wherever the BSDF's is. The learned data is frozen before the
// render, a function of the scene, the settings and the seed alone (not of
// the samples rendered: a shard's image is the single render's), so the image
// is bit-identical for any thread count. Where nothing was learned the
// density is the BSDF's and the samples are Bsdf::sample's.
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

// A distribution over directions: the sphere mapped to the unit square by
// the equal-area cylindrical map (x = (cos theta + 1) / 2, y = phi / 2 pi),
// and a quadtree over the square, finer where the learned energy is (Mueller
// et al.'s directional tree). A cell's mass is (1 - kPriorShare) x its share
// of the points' values + kPriorShare x its area, so every direction has a
// positive density. Sampling descends the tree, halving in x by the halves'
// masses and then in y by the chosen half's, the numbers rescaled at each
// level (a continuous warp of the square); within a leaf cell the direction
// is uniform over its solid angle (the map is equal-area).
class DirectionTree {
 public:
  static constexpr float kPriorShare = 0.1f;
  static constexpr int kMaxDepth = 10;  // cells of 1/4^10 of the sphere at the finest

  static Vec2f to_square(Vec3f w);
  static Vec3f from_square(Vec2f s);

  struct Point {
    Vec2f s;      // the direction, in the square
    float value;  // its weight (>= 0)
  };
  // Builds from weighted points (reordered): a cell splits while it holds
  // more than `split_share` of the total value and at least `min_points`
  // points, to kMaxDepth. With no positive total: empty.
  void build(Point* first, std::size_t count, float split_share, std::size_t min_points);

  bool empty() const { return nodes_.empty(); }
  int cells() const { return static_cast<int>(nodes_.size()) * 3 + 1; }
  // The density per solid angle of w.
  float pdf(Vec3f w) const;
  // A direction and (pdf) its density per solid angle.
  Vec3f sample(Vec2f u, float& pdf) const;

 private:
  struct Node {
    int child[4] = {0, 0, 0, 0};  // quadrant x + 2 y; 0: a leaf cell (node 0 is the root, no one's child)
    float p[4] = {0.25f, 0.25f, 0.25f, 0.25f};  // the quadrants' shares of this node's mass
  };
  int build_node(Point* first, std::size_t count, double total, float area, int depth, float split_share,
                 std::size_t min_points);
  std::vector<Node> nodes_;
};

class PathGuide {
 public:
  static constexpr float kGuided = 0.3f;        // the mixture's share of guided bounces
  static constexpr std::size_t kLeafRecords = 1024;  // a region's most records
  static constexpr std::size_t kMinLeafRecords = 128;  // fewer (of one normal class): nothing guided
  static constexpr float kSplitShare = 0.02f;   // a direction cell with more of a distribution's value splits
  static constexpr std::size_t kMinCellRecords = 64;  // ... if it holds at least this many records
  static constexpr int kIterations = 3;          // training passes, each twice the last one's paths
  static constexpr int kMaxPrepassDepth = 8;    // bounces of a pre-pass path
  static constexpr int64_t kMaxPrepassPaths = int64_t{1} << 18;

  PathGuide() = default;  // inactive
  // Learns from a pre-pass of `paths_per_pixel` x width x height camera paths
  // (at most kMaxPrepassPaths) of at most min(max_depth, kMaxPrepassDepth) bounces.
  static PathGuide learn(const RenderScene& scene, WorkerPool& pool, int paths_per_pixel, int max_depth,
                         uint64_t seed);

  bool active() const { return !tree_.empty(); }
  int leaves() const { return static_cast<int>(leaves_.size()); }

  // A region's learned distribution of directions for one normal class (empty: none).
  struct Leaf {
    DirectionTree directions;
  };
  // The leaf holding p, or nullptr where nothing is guided.
  // The distribution for a point p whose surface has normal n (a region's
  // records are split by the normal's main axis and side: a floor and the
  // wall beside it see their light from different hemispheres), or nullptr
  // where nothing is guided.
  const Leaf* leaf(Vec3f p, Vec3f n) const {
    if (tree_.empty()) return nullptr;
    const Leaf* l = &leaves_[static_cast<std::size_t>(tree_.leaf(p) * kNormalClasses + normal_class(n))];
    return l->directions.empty() ? nullptr : l;
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
    Vec2f s;           // the bounce direction, DirectionTree::to_square
    int normal_class;  // of the vertex's shading normal
    float value;       // luminance of the incident radiance x |cos| / the direction's density
  };

 private:
  // Builds the tree and the leaves from all records so far (reordered).
  void build(std::vector<Record>& records);
  void learn_leaf(Leaf& leaf, const Record* first, std::size_t count, int normal_class) const;

  SpatialTree tree_;
  std::vector<Leaf> leaves_;
};

}  // namespace pt
