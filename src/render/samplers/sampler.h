// Samplers: where the random numbers of every pixel sample come from.
//
// A sampler is a stream of dimensions for one pixel sample at a time (pbrt-v4
// style): start_pixel_sample(x, y, index) positions it at sample `index` of
// pixel (x, y), get_pixel_2d() gives the position inside the pixel (in
// [0,1)^2, handed to the pixel filter), and get_1d()/get_2d() the following
// dimensions in the order the integrator asks for them (lens, then per bounce:
// light choice, light position, lobe, direction, Russian roulette, ...).
//
// Every value is a pure function of (seed, pixel, sample index, dimension):
// never of the thread, the tile or the order of pixels, so images are
// bit-identical for any thread count and tile order, and sample ranges
// rendered separately add up to the same image.
//
// `Sampler` is a small value type: the render loop copies a prototype into
// each task. It is a closed set of kinds (a variant, dispatched with a switch,
// no virtual call per number); a new kind (jittered, Sobol, ...) is one more
// alternative.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "render/samplers/jittered_sampler.h"
#include "render/samplers/sobol_sampler.h"

namespace pt {

// Independent uniform numbers: dimension d of sample i of pixel (x, y) is
// output d of the counter-based stream keyed on hash(seed, x, y, i).
class IndependentSampler {
 public:
  explicit IndependentSampler(uint64_t seed) : seed_(seed) {}

  void start_pixel_sample(int x, int y, int index) {
    const uint64_t pixel = (static_cast<uint64_t>(static_cast<uint32_t>(y)) << 32) | static_cast<uint32_t>(x);
    rng_ = Rng(hash_keys(seed_, pixel, static_cast<uint64_t>(index)));
  }
  float get_1d() { return rng_.next_float(); }
  Vec2f get_2d() {
    const float a = rng_.next_float();
    return {a, rng_.next_float()};
  }
  Vec2f get_pixel_2d() { return get_2d(); }

 private:
  uint64_t seed_;
  Rng rng_{0};
};

// The classic integrators' sampler (docs/rendering.md): the pixel position of
// sample i of n is the pixel centre for n = 1, one jittered sample in each
// cell of a k x k grid for n = k^2 (sample i in cell i mod n, so each pass of
// n samples of a progressive render fills the grid once), and uniform in the
// pixel otherwise; the jitter comes from Rng(hash(seed, y * width + x, i)). Every other dimension
// (the thin lens) comes from a second stream keyed on the same values.
class StratifiedPixelSampler {
 public:
  StratifiedPixelSampler(int spp, uint64_t seed, int width);

  void start_pixel_sample(int x, int y, int index) {
    start(static_cast<uint64_t>(y) * static_cast<uint64_t>(width_) + static_cast<uint64_t>(x), index);
  }
  // The same, given the pixel index y * width + x.
  void start(uint64_t pixel_index, int index);
  float get_1d() { return rest_.next_float(); }
  Vec2f get_2d() {
    const float a = rest_.next_float();
    return {a, rest_.next_float()};
  }
  Vec2f get_pixel_2d() const { return pixel_; }

 private:
  int spp_, grid_;  // grid_ = k if spp = k^2, else 0
  uint64_t seed_;
  int width_;
  Vec2f pixel_;
  Rng rest_{0};
};

class Sampler {
 public:
  Sampler(IndependentSampler s) : impl_(s) {}      // NOLINT: implicit by design
  Sampler(StratifiedPixelSampler s) : impl_(s) {}  // NOLINT
  Sampler(JitteredSampler s) : impl_(s) {}         // NOLINT
  Sampler(SobolSampler s) : impl_(s) {}            // NOLINT

  void start_pixel_sample(int x, int y, int index) {
    std::visit([&](auto& s) { s.start_pixel_sample(x, y, index); }, impl_);
  }
  float get_1d() {
    return std::visit([](auto& s) { return s.get_1d(); }, impl_);
  }
  Vec2f get_2d() {
    return std::visit([](auto& s) { return s.get_2d(); }, impl_);
  }
  Vec2f get_pixel_2d() {
    return std::visit([](auto& s) { return s.get_pixel_2d(); }, impl_);
  }

 private:
  std::variant<IndependentSampler, StratifiedPixelSampler, JitteredSampler, SobolSampler> impl_;
};

// The samplers a user can choose for the path integrator (docs/samplers.md).
enum class SamplerType {
  Random,    // IndependentSampler
  Jittered,  // JitteredSampler
  Sobol,     // SobolSampler (Owen-scrambled, padded)
};

// "random", "jittered", "sobol".
std::vector<std::string> sampler_type_names();
const char* sampler_type_name(SamplerType type);
std::optional<SamplerType> parse_sampler_type(const std::string& name);
// The sampler of `type` for `spp` samples per pixel (jittered stratifies each
// pass of spp samples) and `seed`.
Sampler make_sampler(SamplerType type, int spp, uint64_t seed);

}  // namespace pt
