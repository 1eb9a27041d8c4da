// The directions of an environment map grouped into bins of whole texels (at
// most 32 x 16 of them, in image coordinates), each with the map's own
// importance (luminance x sin theta, as EnvironmentMap's distribution) over
// its texels: what a light guide (light_guide.h) learns a distribution over,
// and how it samples a direction once it has chosen a bin.
#pragma once

#include <vector>

#include "core/sampling.h"
#include "render/lights/environment.h"

namespace pt {

class EnvironmentBins {
 public:
  EnvironmentBins() = default;
  explicit EnvironmentBins(const EnvironmentMap& map);

  int size() const { return bins_x_ * bins_y_; }
  // The bin of image coordinates (EnvironmentMap::direction_to_uv).
  int bin_at(Vec2f uv) const;
  // The probability that the map's own sampling lands in bin b: the bin's
  // share of the importance (0: nothing to sample there).
  float share(int b) const { return share_[static_cast<std::size_t>(b)]; }
  // Image coordinates in bin b, in proportion to the map's importance there:
  // their density is the map's own (EnvironmentMap::pdf_at) / share(b).
  // False if the bin has no importance.
  bool sample(int b, Vec2f u, Vec2f& uv) const;

 private:
  const EnvironmentMap* map_ = nullptr;
  int width_ = 0, height_ = 0, bins_x_ = 0, bins_y_ = 0;
  std::vector<int> x0_, y0_;       // first texel column (row) of each bin column (row), and the end
  std::vector<int> column_bin_, row_bin_;  // per texel column (row): its bin column (row)
  std::vector<Distribution2D> local_;  // per bin, over its texels
  std::vector<float> share_;
};

}  // namespace pt
