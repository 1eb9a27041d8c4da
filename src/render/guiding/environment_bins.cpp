#include "render/guiding/environment_bins.h"

#include <algorithm>
#include <cmath>

namespace pt {

namespace {

constexpr int kMaxBinsX = 32, kMaxBinsY = 16;

// The first texel of each of `bins` bins over `texels` texels, and the end.
std::vector<int> bin_starts(int texels, int bins) {
  std::vector<int> start(static_cast<std::size_t>(bins) + 1);
  for (int b = 0; b <= bins; ++b) start[static_cast<std::size_t>(b)] = b * texels / bins;
  return start;
}

std::vector<int> texel_bins(const std::vector<int>& start) {
  std::vector<int> of(static_cast<std::size_t>(start.back()));
  for (std::size_t b = 0; b + 1 < start.size(); ++b)
    for (int t = start[b]; t < start[b + 1]; ++t) of[static_cast<std::size_t>(t)] = static_cast<int>(b);
  return of;
}

}  // namespace

EnvironmentBins::EnvironmentBins(const EnvironmentMap& map)
    : width_(map.width()),
      height_(map.height()),
      bins_x_(std::min(kMaxBinsX, width_)),
      bins_y_(std::min(kMaxBinsY, height_)) {
  x0_ = bin_starts(width_, bins_x_);
  y0_ = bin_starts(height_, bins_y_);
  column_bin_ = texel_bins(x0_);
  row_bin_ = texel_bins(y0_);
  std::vector<double> weight(static_cast<std::size_t>(size()), 0.0);
  density_.assign(static_cast<std::size_t>(size()), 0.0f);
  for (int y = 0; y < height_; ++y) {
    const double sin_theta = std::sin(kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(height_));
    for (int x = 0; x < width_; ++x)
      weight[static_cast<std::size_t>(row_bin_[static_cast<std::size_t>(y)] * bins_x_ +
                                      column_bin_[static_cast<std::size_t>(x)])] +=
          std::max(0.0f, map.texel_radiance(x, y).luminance()) * sin_theta;
  }
  for (int b = 0; b < size(); ++b) {
    const int bx = b % bins_x_, by = b / bins_x_;
    const float texels = static_cast<float>((x0_[bx + 1] - x0_[bx]) * (y0_[by + 1] - y0_[by]));
    density_[static_cast<std::size_t>(b)] = static_cast<float>(width_) * static_cast<float>(height_) / texels;
  }
  double total = 0.0;
  for (double w : weight) total += w;
  share_.assign(weight.size(), 0.0f);
  for (std::size_t b = 0; b < weight.size(); ++b) share_[b] = total > 0.0 ? static_cast<float>(weight[b] / total) : 0.0f;
}

int EnvironmentBins::bin_at(Vec2f uv) const {
  const int x = std::clamp(static_cast<int>(uv.x * static_cast<float>(width_)), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(uv.y * static_cast<float>(height_)), 0, height_ - 1);
  return row_bin_[static_cast<std::size_t>(y)] * bins_x_ + column_bin_[static_cast<std::size_t>(x)];
}

Vec2f EnvironmentBins::sample(int b, Vec2f u) const {
  const int bx = b % bins_x_, by = b / bins_x_;
  const float x = static_cast<float>(x0_[bx]) + u.x * static_cast<float>(x0_[bx + 1] - x0_[bx]);
  const float y = static_cast<float>(y0_[by]) + u.y * static_cast<float>(y0_[by + 1] - y0_[by]);
  return {std::min(x / static_cast<float>(width_), kOneMinusEpsilon),
          std::min(y / static_cast<float>(height_), kOneMinusEpsilon)};
}

}  // namespace pt
