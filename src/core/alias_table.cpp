#include "core/alias_table.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace pt {

AliasTable::AliasTable(const std::vector<float>& f) : cells_(f.size()) {
  const std::size_t n = f.size();
  if (n == 0) return;
  std::vector<double> p(n);
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    p[i] = (f[i] > 0.0f && std::isfinite(f[i])) ? static_cast<double>(f[i]) : 0.0;
    sum += p[i];
  }
  // Each cell's probability, and its share of a slot of 1 / n, scaled by n.
  std::vector<uint32_t> small, large;
  for (std::size_t i = 0; i < n; ++i) {
    p[i] = sum > 0.0 ? p[i] / sum : 1.0 / static_cast<double>(n);
    cells_[i] = {1.0f, static_cast<uint32_t>(i), static_cast<float>(p[i])};
    p[i] *= static_cast<double>(n);
    (p[i] < 1.0 ? small : large).push_back(static_cast<uint32_t>(i));
  }
  while (!small.empty() && !large.empty()) {
    const uint32_t s = small.back(), l = large.back();
    small.pop_back();
    cells_[s].keep = static_cast<float>(p[s]);
    cells_[s].alias = l;
    p[l] -= 1.0 - p[s];  // l fills the rest of s's slot
    if (p[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What is left holds 1 up to rounding: kept whole (keep = 1, its own alias).
}

std::size_t AliasTable::sample(Vec2f u, Vec2f& rest) const {
  const std::size_t n = cells_.size();
  const double x = static_cast<double>(u.x) * static_cast<double>(n);
  const std::size_t slot = std::min(static_cast<std::size_t>(std::max(x, 0.0)), n - 1);
  rest.x = std::clamp(static_cast<float>(x - static_cast<double>(slot)), 0.0f, kOneMinusEpsilon);
  const Cell& c = cells_[slot];
  if (u.y < c.keep) {
    rest.y = std::min(u.y / c.keep, kOneMinusEpsilon);
    return slot;
  }
  rest.y = std::clamp((u.y - c.keep) / (1.0f - c.keep), 0.0f, kOneMinusEpsilon);
  return c.alias;
}

}  // namespace pt
