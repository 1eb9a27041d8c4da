#include "render/samplers/sampler.h"

#include <cmath>

namespace pt {

namespace {

constexpr uint64_t kLensStream = 0x6c656e73;  // "lens": independent of the film jitter

// Largest k with k * k <= v.
int integer_sqrt(int v) {
  int k = static_cast<int>(std::sqrt(static_cast<double>(v)));
  while (k * k > v) --k;
  while ((k + 1) * (k + 1) <= v) ++k;
  return k;
}

}  // namespace

StratifiedPixelSampler::StratifiedPixelSampler(int spp, uint64_t seed, int width)
    : spp_(spp), grid_(0), seed_(seed), width_(width) {
  const int k = integer_sqrt(spp > 0 ? spp : 1);
  if (spp > 1 && k * k == spp) grid_ = k;
}

void StratifiedPixelSampler::start(uint64_t pixel_index, int index) {
  const uint64_t sample = static_cast<uint64_t>(index);
  if (spp_ <= 1) {
    pixel_ = {0.5f, 0.5f};
  } else {
    Rng rng(hash_keys(seed_, pixel_index, sample));
    const float u = rng.next_float();
    const float v = rng.next_float();
    if (grid_ > 0) {
      // Sample `index` is sample index % spp of pass index / spp: each pass of
      // spp samples fills the grid once (progressive passes, docs/cli.md).
      const int cell = index % spp_;
      const int cx = cell % grid_, cy = cell / grid_;
      const float inv = 1.0f / static_cast<float>(grid_);
      pixel_ = {(static_cast<float>(cx) + u) * inv, (static_cast<float>(cy) + v) * inv};
    } else {
      pixel_ = {u, v};
    }
  }
  rest_ = Rng(hash_keys(hash_keys(seed_, kLensStream), pixel_index, sample));
}

std::vector<std::string> sampler_type_names() { return {"random", "jittered", "sobol"}; }

const char* sampler_type_name(SamplerType type) {
  switch (type) {
    case SamplerType::Random: return "random";
    case SamplerType::Jittered: return "jittered";
    case SamplerType::Sobol: return "sobol";
  }
  return "random";
}

std::optional<SamplerType> parse_sampler_type(const std::string& name) {
  if (name == "random") return SamplerType::Random;
  if (name == "jittered") return SamplerType::Jittered;
  if (name == "sobol") return SamplerType::Sobol;
  return std::nullopt;
}

Sampler make_sampler(SamplerType type, int spp, uint64_t seed) {
  switch (type) {
    case SamplerType::Jittered: return JitteredSampler(spp, seed);
    case SamplerType::Sobol: return SobolSampler(seed);
    case SamplerType::Random: break;
  }
  return IndependentSampler(seed);
}

}  // namespace pt
