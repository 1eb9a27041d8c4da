#include "render/guiding/environment_bins.h"

#include <algorithm>
#include <cmath>

namespace pt {

namespace {

constexpr int kMaxBinsX = 32, kMaxBinsY = 16;
constexpr int kCellSlots = EnvironmentBins::kCells * EnvironmentBins::kCells;  // a bin's entries in cdf_

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

std::vector<int> cells_per_bin(const std::vector<int>& start) {
  std::vector<int> cells(start.size() - 1);
  for (std::size_t b = 0; b + 1 < start.size(); ++b) cells[b] = std::min(EnvironmentBins::kCells, start[b + 1] - start[b]);
  return cells;
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
  cells_x_ = cells_per_bin(x0_);
  cells_y_ = cells_per_bin(y0_);
  // Each cell's importance (the map's luminance x sin theta over its texels).
  std::vector<double> cell(static_cast<std::size_t>(size()) * kCellSlots, 0.0);
  for (int y = 0; y < height_; ++y) {
    const double sin_theta = std::sin(kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(height_));
    const int by = row_bin_[static_cast<std::size_t>(y)];
    for (int x = 0; x < width_; ++x) {
      const int b = by * bins_x_ + column_bin_[static_cast<std::size_t>(x)];
      cell[static_cast<std::size_t>(b) * kCellSlots + static_cast<std::size_t>(cell_at(b, x, y))] +=
          std::max(0.0f, map.texel_radiance(x, y).luminance()) * sin_theta;
    }
  }
  std::vector<double> weight(static_cast<std::size_t>(size()), 0.0);
  cdf_.assign(cell.size(), 0.0f);
  for (int b = 0; b < size(); ++b) {
    const int bx = b % bins_x_, by = b / bins_x_;
    double* w = &cell[static_cast<std::size_t>(b) * kCellSlots];
    double bin = 0.0;
    for (int i = 0; i < kCellSlots; ++i) bin += w[i];
    weight[static_cast<std::size_t>(b)] = bin;
    if (!(bin > 0.0)) {  // nothing to sample here by importance: by area (never chosen by the guide)
      for (int cy = 0; cy < cells_y_[by]; ++cy)
        for (int cx = 0; cx < cells_x_[bx]; ++cx)
          w[cy * kCells + cx] = static_cast<double>(cell_x(bx, cx + 1) - cell_x(bx, cx)) * (cell_y(by, cy + 1) - cell_y(by, cy));
      bin = static_cast<double>(x0_[bx + 1] - x0_[bx]) * (y0_[by + 1] - y0_[by]);
    }
    double sum = 0.0;
    for (int i = 0; i < kCellSlots; ++i) {
      sum += w[i];
      cdf_[static_cast<std::size_t>(b) * kCellSlots + static_cast<std::size_t>(i)] = static_cast<float>(sum / bin);
    }
  }
  double total = 0.0;
  for (double w : weight) total += w;
  share_.assign(weight.size(), 0.0f);
  for (std::size_t b = 0; b < weight.size(); ++b) share_[b] = total > 0.0 ? static_cast<float>(weight[b] / total) : 0.0f;
  coarse_chi2_ = total > 0.0 ? chi2_from_map(map, cell, total) : 0.0f;
  // Each bin's central direction and a bound of the chord to any of its
  // directions: from the centre along the meridian to the direction's polar
  // angle (at most half the bin's polar span), then along that parallel (at
  // most sin(theta) x half its azimuth span); a chord is at most the arc. The
  // small margin covers the float rounding of the direction <-> image mapping.
  for (int b = 0; b < size(); ++b) {
    const int bx = b % bins_x_, by = b / bins_x_;
    const float u0 = static_cast<float>(x0_[bx]) / static_cast<float>(width_);
    const float u1 = static_cast<float>(x0_[bx + 1]) / static_cast<float>(width_);
    const float v0 = static_cast<float>(y0_[by]) / static_cast<float>(height_);
    const float v1 = static_cast<float>(y0_[by + 1]) / static_cast<float>(height_);
    const Vec3f axis = map.uv_to_direction({0.5f * (u0 + u1), 0.5f * (v0 + v1)});
    const float max_sin = (v0 <= 0.5f && v1 >= 0.5f) ? 1.0f : std::max(std::sin(kPi * v0), std::sin(kPi * v1));
    axis_x_.push_back(axis.x);
    axis_y_.push_back(axis.y);
    axis_z_.push_back(axis.z);
    radius_.push_back(0.5f * kPi * (v1 - v0) + max_sin * kPi * (u1 - u0) + 1e-3f);
  }
}

// Sum over texels of p^2 / q - 1, p the texel's share of the map's importance, q
// the coarse distribution's probability of the texel (its cell's share over the
// cell's texel count); `cell` is each cell's importance, `total` the map's.
float EnvironmentBins::chi2_from_map(const EnvironmentMap& map, const std::vector<double>& cell, double total) const {
  double sum = 0.0;
  for (int y = 0; y < height_; ++y) {
    const double sin_theta = std::sin(kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(height_));
    const int by = row_bin_[static_cast<std::size_t>(y)];
    for (int x = 0; x < width_; ++x) {
      const double t = std::max(0.0f, map.texel_radiance(x, y).luminance()) * sin_theta;
      if (!(t > 0.0)) continue;
      const int bx = column_bin_[static_cast<std::size_t>(x)], b = by * bins_x_ + bx, i = cell_at(b, x, y);
      const int cx = i % kCells, cy = i / kCells;
      const double texels = static_cast<double>(cell_x(bx, cx + 1) - cell_x(bx, cx)) * (cell_y(by, cy + 1) - cell_y(by, cy));
      sum += t * t * texels / cell[static_cast<std::size_t>(b) * kCellSlots + static_cast<std::size_t>(i)];
    }
  }
  return static_cast<float>(sum / total - 1.0);
}

int EnvironmentBins::cell_at(int b, int x, int y) const {
  const int bx = b % bins_x_, by = b / bins_x_;
  // The last cell whose first texel is at most x: cell c starts at x0 + floor(c w / n).
  const int w = x0_[bx + 1] - x0_[bx], h = y0_[by + 1] - y0_[by];
  const int cx = std::clamp(((x - x0_[bx] + 1) * cells_x_[bx] - 1) / w, 0, cells_x_[bx] - 1);
  const int cy = std::clamp(((y - y0_[by] + 1) * cells_y_[by] - 1) / h, 0, cells_y_[by] - 1);
  return cy * kCells + cx;
}

int EnvironmentBins::bin_at(Vec2f uv) const {
  const int x = std::clamp(static_cast<int>(uv.x * static_cast<float>(width_)), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(uv.y * static_cast<float>(height_)), 0, height_ - 1);
  return row_bin_[static_cast<std::size_t>(y)] * bins_x_ + column_bin_[static_cast<std::size_t>(x)];
}

Vec2f EnvironmentBins::sample(int b, Vec2f u) const {
  const int bx = b % bins_x_, by = b / bins_x_;
  const float* cdf = &cdf_[static_cast<std::size_t>(b) * kCellSlots];
  // The first cell whose cumulative probability passes u.x (a cell of probability 0 never is);
  // rounding can leave u.x at or past the last sum: the last cell with a positive probability.
  int i = static_cast<int>(std::upper_bound(cdf, cdf + kCellSlots, u.x) - cdf);
  if (i == kCellSlots) {
    i = kCellSlots - 1;
    while (i > 0 && cdf[i] == cdf[i - 1]) --i;
  }
  const float lo = i > 0 ? cdf[i - 1] : 0.0f, p = cdf[i] - lo;
  const float v = p > 0.0f ? std::clamp((u.x - lo) / p, 0.0f, kOneMinusEpsilon) : 0.5f;
  const int cx = i % kCells, cy = i / kCells;
  const int xa = cell_x(bx, cx), xb = cell_x(bx, cx + 1), ya = cell_y(by, cy), yb = cell_y(by, cy + 1);
  const float x = static_cast<float>(xa) + v * static_cast<float>(xb - xa);
  const float y = static_cast<float>(ya) + u.y * static_cast<float>(yb - ya);
  return {std::min(x / static_cast<float>(width_), kOneMinusEpsilon),
          std::min(y / static_cast<float>(height_), kOneMinusEpsilon)};
}

float EnvironmentBins::density(int b, Vec2f uv) const {
  const int bx = b % bins_x_, by = b / bins_x_;
  const int x = std::clamp(static_cast<int>(uv.x * static_cast<float>(width_)), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(uv.y * static_cast<float>(height_)), 0, height_ - 1);
  const int i = cell_at(b, x, y);
  const float* cdf = &cdf_[static_cast<std::size_t>(b) * kCellSlots];
  const float p = cdf[i] - (i > 0 ? cdf[i - 1] : 0.0f);
  const int cx = i % kCells, cy = i / kCells;
  const float texels = static_cast<float>((cell_x(bx, cx + 1) - cell_x(bx, cx)) * (cell_y(by, cy + 1) - cell_y(by, cy)));
  return p * static_cast<float>(width_) * static_cast<float>(height_) / texels;
}

std::size_t EnvironmentBins::table_bytes() const {
  return (cdf_.size() + share_.size() + axis_x_.size() + axis_y_.size() + axis_z_.size() + radius_.size()) * sizeof(float) +
         (x0_.size() + y0_.size() + column_bin_.size() + row_bin_.size() + cells_x_.size() + cells_y_.size()) * sizeof(int);
}

}  // namespace pt
