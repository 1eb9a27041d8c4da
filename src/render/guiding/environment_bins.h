// The directions of an environment map grouped into bins of whole texels (at
// most 32 x 16 of them, in image coordinates), each with its share of the
// map's importance (luminance x sin theta, as EnvironmentMap's distribution):
// what a light guide (light_guide.h) learns a distribution over. Within a bin
// it samples uniformly in image coordinates (a sky is smooth over a bin; the
// guide's mixture keeps the map's own sampling for its sharp features).
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
  // Image coordinates in bin b, uniformly, with density density(b) in [0, 1)^2.
  Vec2f sample(int b, Vec2f u) const;
  float density(int b) const { return density_[static_cast<std::size_t>(b)]; }

 private:
  int width_ = 0, height_ = 0, bins_x_ = 0, bins_y_ = 0;
  std::vector<int> x0_, y0_;       // first texel column (row) of each bin column (row), and the end
  std::vector<int> column_bin_, row_bin_;  // per texel column (row): its bin column (row)
  std::vector<float> share_, density_;
};

}  // namespace pt
