// The directions of an environment map grouped into bins of whole texels (at
// most 32 x 16 of them, in image coordinates), each with its share of the
// map's importance (luminance x sin theta, as EnvironmentMap's distribution):
// what a light guide (light_guide.h) learns a distribution over. Within a bin
// it samples a coarse importance grid of at most kCells x kCells cells of
// whole texels (each cell in proportion to its share of the bin's importance,
// then uniformly in the cell, in image coordinates): the bin's bright part (a
// sun disc in the map, a bright horizon) gets the samples the map's own
// distribution would give it, at a table of bins x kCells^2 floats for the
// whole map (128 KiB at 32 x 16 bins), shared by every leaf of the guide.
#pragma once

#include <algorithm>
#include <vector>

#include "core/sampling.h"
#include "render/lights/environment.h"

namespace pt {

class EnvironmentBins {
 public:
  static constexpr int kCells = 8;  // a bin's importance grid's most cells per side

  EnvironmentBins() = default;
  explicit EnvironmentBins(const EnvironmentMap& map);

  int size() const { return bins_x_ * bins_y_; }
  // An upper bound of max(0, cos) between any direction of bin b and any unit
  // vector within chord `slack` of the unit vector n: max(0, n . axis(b) +
  // radius(b) + slack), radius(b) bounding the chord from the bin's central
  // direction to any of its directions (for such x and m: m . x <= n . axis
  // + |x - axis| + |m - n|). Positive wherever some direction of the bin is
  // in front of some such m.
  float cosine_bound(int b, Vec3f n, float slack) const {
    const std::size_t i = static_cast<std::size_t>(b);
    return std::max(0.0f, n.x * axis_x_[i] + n.y * axis_y_[i] + n.z * axis_z_[i] + radius_[i] + slack);
  }
  // The bin of image coordinates (EnvironmentMap::direction_to_uv).
  int bin_at(Vec2f uv) const;
  // The probability that the map's own sampling lands in bin b: the bin's
  // share of the importance (0: nothing to sample there).
  float share(int b) const { return share_[static_cast<std::size_t>(b)]; }
  // Image coordinates in bin b, from its importance grid, and their density
  // in [0, 1)^2 (density(b, uv) for uv in bin b).
  Vec2f sample(int b, Vec2f u) const;
  float density(int b, Vec2f uv) const;
  // The bytes of the bins' tables (for the docs' figures and tests).
  std::size_t table_bytes() const;
  // The chi-square divergence of the coarse distribution (a bin by its share,
  // then its grid) from the map's own: the relative variance its samples add
  // to an unoccluded estimate of the map's power, where the map's own
  // sampling adds none. Near 0 for a smooth sky; large where a sun disc or
  // other small bright texels sit in cells of dim ones.
  float coarse_chi2() const { return coarse_chi2_; }

 private:
  // Cell (cx, cy) of bin (bx, by): its first texel column (row), and the end.
  int cell_x(int bx, int cx) const { return x0_[bx] + cx * (x0_[bx + 1] - x0_[bx]) / cells_x_[bx]; }
  int cell_y(int by, int cy) const { return y0_[by] + cy * (y0_[by + 1] - y0_[by]) / cells_y_[by]; }
  int cell_at(int b, int x, int y) const;  // the cell of texel (x, y) in bin b: cy * kCells + cx
  float chi2_from_map(const EnvironmentMap& map, const std::vector<double>& cell, double total) const;

  int width_ = 0, height_ = 0, bins_x_ = 0, bins_y_ = 0;
  std::vector<int> x0_, y0_;       // first texel column (row) of each bin column (row), and the end
  std::vector<int> column_bin_, row_bin_;  // per texel column (row): its bin column (row)
  std::vector<int> cells_x_, cells_y_;     // per bin column (row): cells per side, at most kCells
  std::vector<float> share_;
  std::vector<float> axis_x_, axis_y_, axis_z_, radius_;  // per bin: its central direction, and the chord bound
  // Per bin, kCells^2 entries (row-major, cy * kCells + cx; unused ones 0): the
  // cumulative probability of the cells up to and including each.
  std::vector<float> cdf_;
  float coarse_chi2_ = 0.0f;
};

}  // namespace pt
