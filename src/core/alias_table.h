// Walker's alias method (Vose's construction): a discrete distribution over n
// cells sampled in constant time, one table entry read per sample.
//
// Beside the inversion of a CDF (Distribution1D, core/sampling.h), which maps u
// to cells in order and so keeps a stratified u stratified, the alias method
// scatters u over the cells; in return a sample reads one entry instead of a
// chain of dependent probes, which matters where the table is far larger than
// the caches (an environment map's 512k texels: EnvironmentMap).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace pt {

class AliasTable {
 public:
  AliasTable() = default;
  // Cell i with probability f[i] / sum f (values that are negative or not
  // finite count as 0). If every value is zero the distribution is uniform.
  explicit AliasTable(const std::vector<float>& f);

  std::size_t size() const { return cells_.size(); }
  // A cell from u in [0, 1)^2 with probability pmf(cell), and in `rest` what is
  // left of u: uniform on [0, 1)^2 and independent of the cell (u.x's low
  // digits, and u.y rescaled by the branch it took).
  std::size_t sample(Vec2f u, Vec2f& rest) const;
  float pmf(std::size_t i) const { return i < cells_.size() ? cells_[i].pmf : 0.0f; }

 private:
  struct Cell {
    float keep;      // the probability of keeping this cell rather than its alias
    uint32_t alias;  // the cell that fills the rest of this one's slot
    float pmf;       // this cell's own probability
  };
  std::vector<Cell> cells_;
};

}  // namespace pt
