// Film::add_film: the state of one film (a shard: a sample range or a tile of
// the frame) added into another, exactly (docs/distributed.md).
#include <algorithm>
#include <string>

#include "render/film/film.h"

namespace pt {
namespace {

bool same_aovs(const std::vector<AovRequest>& a, const std::vector<AovRequest>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].type != b[i].type || a[i].channel_type != b[i].channel_type || a[i].ranks != b[i].ranks) return false;
  return true;
}

}  // namespace

bool Film::add_film(const Film& other, const PixelRect& c, bool other_first, std::string& error) {
  if (other.width_ != width_ || other.height_ != height_) {
    error = "the film is " + std::to_string(other.width_) + "x" + std::to_string(other.height_) + ", not " +
            std::to_string(width_) + "x" + std::to_string(height_);
    return false;
  }
  if (!other.crop_.contains(c) || !crop_.contains(c)) {
    error = "pixels " + c.text() + " are not inside both " + other.crop_.text() + " and " + crop_.text();
    return false;
  }
  if (!same_aovs(other.aovs_, aovs_)) {
    error = "its AOVs differ";
    return false;
  }
  const auto sums = static_cast<std::size_t>(sum_stride_), values = static_cast<std::size_t>(value_stride_);
  for (int y = c.y0; y < c.y1; ++y) {
    const std::size_t from = other.index(c.x0, y);
    const std::size_t to = index(c.x0, y);
    for (std::size_t i = 0; i < static_cast<std::size_t>(c.width()); ++i) {
      pixels_[to + i].add(other.pixels_[from + i]);
      add_sums(to + i, other.aov_sums_.data() + (from + i) * sums);
    }
    if (values == 0) continue;
    for (std::size_t i = 0; i < static_cast<std::size_t>(c.width()); ++i)
      add_values(to + i, other.aov_values_.data() + (from + i) * values, other_first);
  }
  return true;
}

void Film::add_values(std::size_t pixel, const double* s, bool other_first) {
  double* d = aov_values_.data() + pixel * static_cast<std::size_t>(value_stride_);
  for (const std::size_t a : value_layers_) {
    const AovInfo& info = *info_[a];
    double* dv = d + value_offset_[a];
    const double* sv = s + value_offset_[a];
    if (info.accumulation == Accumulation::Max) {
      dv[0] = std::max(dv[0], sv[0]);
    } else if (info.accumulation == Accumulation::FirstSample && sv[info.channels] != 0.0 &&
               (other_first || dv[info.channels] == 0.0)) {
      std::copy(sv, sv + info.values, dv);
    }
  }
}

void Film::first_values(double* v) const {
  for (const std::size_t a : value_layers_) {
    const AovInfo& info = *info_[a];
    double* d = v + value_offset_[a];
    const auto n = static_cast<std::size_t>(info.values);
    // add_values into zeros: std::max(0.0, x), so -0.0 and NaN give +0.0
    // (and negatives 0); first-sample values copied only when flagged (the
    // flag != 0.0: -0.0 is not, NaN is); nothing else is added.
    if (info.accumulation == Accumulation::Max) {
      d[0] = std::max(0.0, d[0]);
      if (n > 1) std::fill(d + 1, d + n, 0.0);
    } else if (info.accumulation != Accumulation::FirstSample || !(d[info.channels] != 0.0)) {
      std::fill(d, d + n, 0.0);
    }
  }
}

}  // namespace pt
