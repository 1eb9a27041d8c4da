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
    : map_(&map),
      width_(map.width()),
      height_(map.height()),
      bins_x_(std::min(kMaxBinsX, width_)),
      bins_y_(std::min(kMaxBinsY, height_)) {
  x0_ = bin_starts(width_, bins_x_);
  y0_ = bin_starts(height_, bins_y_);
  column_bin_ = texel_bins(x0_);
  row_bin_ = texel_bins(y0_);
  local_.resize(static_cast<std::size_t>(size()));
  std::vector<double> weight(static_cast<std::size_t>(size()), 0.0);
  for (int by = 0; by < bins_y_; ++by)
    for (int bx = 0; bx < bins_x_; ++bx) {
      const int nx = x0_[bx + 1] - x0_[bx], ny = y0_[by + 1] - y0_[by];
      std::vector<float> f(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
      double sum = 0.0;
      for (int y = 0; y < ny; ++y) {
        const float v = (static_cast<float>(y0_[by] + y) + 0.5f) / static_cast<float>(height_);
        const float sin_theta = std::sin(kPi * v);
        for (int x = 0; x < nx; ++x) {
          const float value = std::max(0.0f, map.texel_radiance(x0_[bx] + x, y0_[by] + y).luminance()) * sin_theta;
          f[static_cast<std::size_t>(y) * nx + x] = value;
          sum += value;
        }
      }
      const std::size_t b = static_cast<std::size_t>(by) * bins_x_ + bx;
      weight[b] = sum;
      if (sum > 0.0) local_[b] = Distribution2D(f, nx, ny);
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

bool EnvironmentBins::sample(int b, Vec2f u, Vec2f& uv) const {
  if (!(share(b) > 0.0f)) return false;
  const int bx = b % bins_x_, by = b / bins_x_;
  const int nx = x0_[bx + 1] - x0_[bx], ny = y0_[by + 1] - y0_[by];
  float local_pdf = 0.0f;
  const Vec2f l = local_[static_cast<std::size_t>(b)].sample(u, &local_pdf);
  if (!(local_pdf > 0.0f)) return false;
  uv = Vec2f((static_cast<float>(x0_[bx]) + l.x * static_cast<float>(nx)) / static_cast<float>(width_),
             (static_cast<float>(y0_[by]) + l.y * static_cast<float>(ny)) / static_cast<float>(height_));
  return true;
}

}  // namespace pt
