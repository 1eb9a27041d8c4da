#include "render/film/film.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <utility>
#include <sstream>
#include <tuple>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

namespace pt {

namespace {

PixelRect clip(PixelRect r, int width, int height) {
  r.x0 = std::clamp(r.x0, 0, width);
  r.x1 = std::clamp(r.x1, r.x0, width);
  r.y0 = std::clamp(r.y0, 0, height);
  r.y1 = std::clamp(r.y1, r.y0, height);
  return r;
}

// Products of two floats: exact in double, rounded once by ExactSum.
void add_weighted(ExactSum* s, float w, float a, float b, float c) {
  s[0].add(static_cast<double>(w) * a);
  s[1].add(static_cast<double>(w) * b);
  s[2].add(static_cast<double>(w) * c);
}

void add_weighted(ExactSum* s, float w, RGB v) { add_weighted(s, w, v.r, v.g, v.b); }

// First-sample layers: n values and a flag (1 once set).
void set_first(double* s, int n, const float* v) {
  if (s[n] != 0.0) return;
  for (int c = 0; c < n; ++c) s[c] = v[c];
  s[n] = 1.0;
}

// Ranked (Cryptomatte) layers: `ranks` slots of (id, weight sum), the id's
// 32 bits held as the integer of an ExactSum (0 marks a free slot: no name
// hashes to 0), in increasing order of those bits, free slots last. The slots
// keep the `ranks` smallest ids seen: a weight goes to its id's slot; a new id
// smaller than one kept takes its place in the order and the largest kept id
// falls out, for good (it can never again be among the smallest), and a new
// id larger than every one of full slots is dropped. Which ids are kept is
// thus a function of the set of ids the pixel's samples hit, not of their
// order or of how they are grouped into passes, shards and merges, and every
// id kept has the weight of every sample that hit it: sums and merges are
// exact (docs/output.md). (Cycles keeps the first ids met, which depends on
// the grouping.)
uint32_t slot_id(const ExactSum& s) { return static_cast<uint32_t>(s.raw()); }

void add_ranked(ExactSum* slots, int ranks, uint32_t id, const ExactSum& w) {
  if (id == 0) return;  // the camera ray hit nothing
  int k = 0;
  while (k < ranks && !slots[2 * k].is_zero() && slot_id(slots[2 * k]) < id) ++k;
  if (k == ranks) return;
  if (!slots[2 * k].is_zero() && slot_id(slots[2 * k]) == id) {
    slots[2 * k + 1].add(w);
    return;
  }
  for (int j = ranks - 1; j > k; --j) {
    slots[2 * j] = slots[2 * j - 2];
    slots[2 * j + 1] = slots[2 * j - 1];
  }
  slots[2 * k].set_raw(id);
  slots[2 * k + 1] = w;
}

void add_ranked(ExactSum* slots, int ranks, float id, float w) {
  add_ranked(slots, ranks, std::bit_cast<uint32_t>(id), ExactSum(static_cast<double>(w)));
}

// The ranked ids and coverages (weight / the pixel's total weight, clamped
// to [0, 1]) into out[0 .. 2 * ranks), highest coverage first (ties: the
// smaller id first); free slots give (0, 0). The used slots come first (the
// ids in increasing order: add_ranked), so only they are sorted; their ids
// differ, so the order is total and any sort gives it.
void ranked_values(const ExactSum* slots, int ranks, const ExactSum& weight, float* out) {
  std::fill(out, out + 2 * ranks, 0.0f);
  if (weight.is_zero()) return;
  std::array<int, kCryptomatteMaxRanks> order{};
  std::array<double, kCryptomatteMaxRanks> w{};
  std::array<float, kCryptomatteMaxRanks> id{};
  int used = 0;
  for (; used < ranks && !slots[2 * used].is_zero(); ++used) {
    const auto i = static_cast<std::size_t>(used);
    w[i] = slots[2 * used + 1].value();
    id[i] = std::bit_cast<float>(slot_id(slots[2 * used]));
    // Insertion: a few slots at most.
    int k = used;
    for (; k > 0; --k) {
      const auto o = static_cast<std::size_t>(order[static_cast<std::size_t>(k - 1)]);
      if (std::make_tuple(-w[o], id[o]) < std::make_tuple(-w[i], id[i])) break;
      order[static_cast<std::size_t>(k)] = static_cast<int>(o);
    }
    order[static_cast<std::size_t>(k)] = used;
  }
  const double total = weight.value();
  for (int k = 0; k < used; ++k) {
    const auto o = static_cast<std::size_t>(order[static_cast<std::size_t>(k)]);
    out[2 * k] = id[o];
    out[2 * k + 1] = static_cast<float>(std::clamp(w[o] / total, 0.0, 1.0));
  }
}

// Filtered averages: `n` sums `s` over the pixel's weight `weight` (its
// weight sum's value, not zero) into `out`. The values first, then the
// divisions in one loop (which the compiler gives two at a time).
void average(const ExactSum* s, int n, double weight, float* out) {
  constexpr int kBatch = 16;
  for (int first = 0; first < n; first += kBatch) {
    const int m = std::min(kBatch, n - first);
    double v[kBatch];
    for (int c = 0; c < m; ++c) v[c] = s[first + c].value();
    for (int c = 0; c < m; ++c) out[first + c] = static_cast<float>(v[c] / weight);
  }
}

}  // namespace

std::string PixelRect::text() const {
  std::string s = "[";  // appended, not "[" + ...: GCC 12 warns falsely about that (-Wrestrict)
  s += std::to_string(x0) + "," + std::to_string(x1) + ")x[" + std::to_string(y0) + "," + std::to_string(y1) + ")";
  return s;
}

void NonFiniteReport::record(int px, int py, int sample_index, RGB v) {
  if (std::isnan(v.r) || std::isnan(v.g) || std::isnan(v.b)) {
    ++nan;
  } else if (v.r == kInfinity || v.g == kInfinity || v.b == kInfinity) {
    ++pos_inf;
  } else {
    ++neg_inf;
  }
  if (!has_first || std::tie(py, px, sample_index) < std::tie(y, x, sample)) {
    has_first = true;
    x = px;
    y = py;
    sample = sample_index;
    value = v;
  }
}

void NonFiniteReport::merge(const NonFiniteReport& o) {
  nan += o.nan;
  pos_inf += o.pos_inf;
  neg_inf += o.neg_inf;
  if (o.has_first && (!has_first || std::tie(o.y, o.x, o.sample) < std::tie(y, x, sample))) {
    has_first = true;
    x = o.x;
    y = o.y;
    sample = o.sample;
    value = o.value;
  }
}

std::string NonFiniteReport::describe() const {
  std::ostringstream os;
  os << total() << " non-finite sample" << (total() == 1 ? "" : "s") << " (" << nan << " NaN, " << pos_inf
     << " +Inf, " << neg_inf << " -Inf)";
  if (has_first)
    os << "; first at pixel (" << x << ", " << y << ") sample " << sample << ": (" << value.r << ", " << value.g
       << ", " << value.b << ")";
  return os.str();
}

Film::Film(int width, int height) : Film(width, height, PixelRect{0, 0, width, height}) {}

Film::Film(int width, int height, PixelRect crop, std::vector<AovRequest> aovs)
    : width_(std::max(width, 0)), height_(std::max(height, 0)), crop_(clip(crop, width_, height_)),
      pixels_(static_cast<std::size_t>(crop_.width()) * static_cast<std::size_t>(crop_.height())),
      aovs_(std::move(aovs)) {
  int resolved_out = 4;  // a pixel's resolved channels: the beauty's, then each AOV's
  for (AovRequest& r : aovs_) {
    const AovInfo& info = aov_info(r.type);
    r.ranks = info.accumulation != Accumulation::Ranked ? 0
              : r.ranks <= 0                             ? kCryptomatteDefaultRanks
                                                         : std::min(r.ranks, kCryptomatteMaxRanks);
    sum_offset_.push_back(sum_stride_);
    value_offset_.push_back(value_stride_);
    channel_count_.push_back(aov_channel_count(r));
    info_.push_back(&info);
    const int ranks = info.accumulation == Accumulation::Ranked ? r.ranks : 0, count = aov_state_sums(r);
    if (ranks == 0 && !sum_runs_.empty() && sum_runs_.back().ranks == 0) {
      sum_runs_.back().count += count;
    } else if (count > 0) {
      sum_runs_.push_back({sum_stride_, count, ranks});
    }
    averaged_.push_back(info.accumulation == Accumulation::FilteredAverage && count == channel_count_.back());
    if (averaged_.back() != 0) {
      const int out = resolved_out, n = count;
      if (info.type == AovType::Albedo) albedo_out_ = out;
      if (!average_runs_.empty() && average_runs_.back().sum + average_runs_.back().count == sum_stride_ &&
          average_runs_.back().out + average_runs_.back().count == out) {
        average_runs_.back().count += n;
      } else {
        average_runs_.push_back({sum_stride_, out, n});
      }
    }
    if (info.values > 0) value_layers_.push_back(value_offset_.size() - 1);
    resolved_out += channel_count_.back();
    sum_stride_ += count;
    value_stride_ += aov_state_values(r);
    if (aov_bit(r.type) & kGeometryAovs) wants_geometry_ = true;
    if (info.lighting) wants_lighting_ = true;
  }
  aov_sums_.assign(pixels_.size() * static_cast<std::size_t>(sum_stride_), ExactSum{});
  aov_values_.assign(pixels_.size() * static_cast<std::size_t>(value_stride_), 0.0);
  init_state_layout();
}

Image Film::image() const {
  Image out(crop_.width(), crop_.height());
  for (std::size_t i = 0; i < pixels_.size(); ++i) out.pixels[i] = pixels_[i].value();
  return out;
}

void Film::clear() {
  std::fill(pixels_.begin(), pixels_.end(), PixelSum{});
  std::fill(aov_sums_.begin(), aov_sums_.end(), ExactSum{});
  std::fill(aov_values_.begin(), aov_values_.end(), 0.0);
  non_finite_ = {};
}

AovScratch Film::make_scratch() const {
  AovScratch scratch;
  scratch.sums.resize(static_cast<std::size_t>(sum_stride_));
  scratch.values.resize(static_cast<std::size_t>(value_stride_));
  return scratch;
}

void Film::accumulate(AovScratch& scratch, const AovSample& a, RGB radiance, float w, bool non_finite) const {
  for (std::size_t i = 0; i < aovs_.size(); ++i) {
    ExactSum* s = scratch.sums.data() + sum_offset_[i];
    double* v = scratch.values.data() + value_offset_[i];
    switch (aovs_[i].type) {
      case AovType::Albedo: add_weighted(s, w, a.albedo); break;
      case AovType::Normal: add_weighted(s, w, a.normal.x, a.normal.y, a.normal.z); break;
      case AovType::Position: {
        const float p[3] = {a.position.x, a.position.y, a.position.z};
        set_first(v, 3, p);
        break;
      }
      case AovType::Depth: set_first(v, 1, &a.depth); break;
      case AovType::ObjectId: {
        const float id = static_cast<float>(a.object);
        set_first(v, 1, &id);
        break;
      }
      case AovType::MaterialId: {
        const float id = static_cast<float>(a.material);
        set_first(v, 1, &id);
        break;
      }
      case AovType::Emission: if (!non_finite) add_weighted(s, w, a.emission); break;
      case AovType::DiffuseDirect: if (!non_finite) add_weighted(s, w, a.diffuse_direct); break;
      case AovType::DiffuseIndirect: if (!non_finite) add_weighted(s, w, a.diffuse_indirect); break;
      case AovType::SpecularDirect: if (!non_finite) add_weighted(s, w, a.specular_direct); break;
      case AovType::SpecularIndirect: if (!non_finite) add_weighted(s, w, a.specular_indirect); break;
      case AovType::Ambient: if (!non_finite) add_weighted(s, w, a.ambient); break;
      case AovType::Variance:
        if (!non_finite) {
          for (int c = 0; c < 3; ++c) {
            const double x = radiance[c];
            s[c].add(x);
            s[3 + c].add(x * x);  // a float squared: exact in double
          }
        }
        break;
      case AovType::Samples: break;  // the beauty's count
      case AovType::NonFinite: if (non_finite) v[0] = 1.0; break;
      case AovType::CryptoObject: add_ranked(s, aovs_[i].ranks, a.crypto_object, w); break;
      case AovType::CryptoMaterial: add_ranked(s, aovs_[i].ranks, a.crypto_material, w); break;
    }
  }
}

void Film::add_aovs(int x, int y, const AovScratch& scratch) {
  const std::size_t pixel = index(x, y);
  add_sums(pixel, scratch.sums.data());
  double* values = aov_values_.data() + pixel * static_cast<std::size_t>(value_stride_);
  for (std::size_t i = 0; i < aovs_.size(); ++i) {
    const AovInfo& info = *info_[i];
    double* d = values + value_offset_[i];
    const double* s = scratch.values.data() + value_offset_[i];
    if (info.accumulation == Accumulation::FirstSample) {
      if (d[info.channels] == 0.0 && s[info.channels] != 0.0) std::copy(s, s + info.values, d);
    } else if (info.accumulation == Accumulation::Max) {
      d[0] = std::max(d[0], s[0]);
    }
  }
}

namespace {
// Whether the first `used` ranks of Cryptomatte slots `slots` hold ids (32
// bits, a float's that is neither 0, denormal nor infinite or NaN) in
// increasing order.
bool ranked_ids(const ExactSum* slots, int used) {
  uint32_t previous = 0;
  for (int k = 0; k < used; ++k) {
    const ExactSum& id = slots[2 * k];
    const uint32_t bits = slot_id(id), exponent = (bits >> 23) & 0xffu;
    if (id.raw() >> 32 != 0 || bits <= previous || exponent == 0 || exponent == 255) return false;
    previous = bits;
  }
  return true;
}

// Whether a Cryptomatte layer's slots `slots` of `ranks` ranks are as
// add_ranked leaves them: the ranks before the first free one (id 0) hold
// ids in increasing order; from it on, ids and weights are all 0.
bool valid_layer(const ExactSum* slots, int ranks) {
  int used = 0;
  while (used < ranks && !slots[2 * used].is_zero()) ++used;
  UInt128 rest = 0;
  for (int j = 2 * used; j < 2 * ranks; ++j) rest |= slots[j].raw();
  return rest == 0 && ranked_ids(slots, used);
}
}  // namespace

bool Film::valid_ranked(const ExactSum* s) const {
  for (const SumRun& run : sum_runs_)
    if (run.ranks > 0 && !valid_layer(s + run.offset, run.ranks)) return false;
  return true;
}

bool Film::valid_ranked(const ExactSum* s, const std::array<uint64_t, kStateWords>& held,
                        const std::array<uint64_t, kStateWords>& varying) const {
  static_assert(kStateWords == 2 && 2 * kCryptomatteMaxRanks < 64, "a layer's slots are bits of one 128-bit mask");
  const UInt128 h = held[0] | static_cast<UInt128>(held[1]) << 64;
  const UInt128 zero = varying[0] | static_cast<UInt128>(varying[1]) << 64;
  for (const SumRun& run : sum_runs_) {
    if (run.ranks == 0) continue;
    const auto first = kAovSlot + static_cast<std::size_t>(run.offset);
    const uint64_t all = (uint64_t{1} << (2 * run.ranks)) - 1;  // the layer's slots, ids at the even bits
    if ((static_cast<uint64_t>(zero >> first) & all) != all) {  // a default not 0: the slots themselves
      if (!valid_layer(s + run.offset, run.ranks)) return false;
      continue;
    }
    // Every default 0: a slot is not 0 exactly when it is held.
    const uint64_t bits = static_cast<uint64_t>(h >> first) & all;
    int used = 0;
    while (used < run.ranks && ((bits >> (2 * used)) & 1) != 0) ++used;
    if ((bits >> (2 * used)) != 0 || !ranked_ids(s + run.offset, used)) return false;
  }
  return true;
}

namespace {
// Adds a Cryptomatte layer's slots `s` (`ranks` ranks) into `d`: its used ranks, by id (add_ranked).
void add_layer(ExactSum* d, const ExactSum* s, int ranks) {
  for (int k = 0; k < ranks && !s[2 * k].is_zero(); ++k) add_ranked(d, ranks, slot_id(s[2 * k]), s[2 * k + 1]);
}
}  // namespace

void Film::add_sums(std::size_t pixel, const ExactSum* s) {
  ExactSum* d = aov_sums_.data() + pixel * static_cast<std::size_t>(sum_stride_);
  for (const SumRun& run : sum_runs_) {
    ExactSum* dl = d + run.offset;
    const ExactSum* sl = s + run.offset;
    if (run.ranks > 0) {
      add_layer(dl, sl, run.ranks);
    } else {
      for (int k = 0; k < run.count; ++k) dl[k].add(sl[k]);
    }
  }
}

void Film::add_sums(std::size_t pixel, const ExactSum* s, const std::array<uint64_t, kStateWords>& slots) {
  ExactSum* d = aov_sums_.data() + pixel * static_cast<std::size_t>(sum_stride_);
  for_each_slot(slots, plain_sum_slots_, [&](std::size_t k) { d[k - kAovSlot].add(s[k - kAovSlot]); });
  for (const SumRun& run : sum_runs_)
    if (run.ranks > 0) add_layer(d + run.offset, s + run.offset, run.ranks);
}

void Film::aov_values(std::size_t layer, std::size_t pixel, float* out) const {
  const PixelSum& p = pixels_[pixel];
  aov_values(layer, p, p.weight.is_zero() ? 0.0 : p.weight.value(),
             aov_sums_.data() + pixel * static_cast<std::size_t>(sum_stride_) + sum_offset_[layer],
             aov_values_.data() + pixel * static_cast<std::size_t>(value_stride_) + value_offset_[layer], out);
}

void Film::aov_values(std::size_t layer, const PixelSum& p, double weight, const ExactSum* s, const double* d,
                      float* out) const {
  const AovInfo& info = *info_[layer];
  const int n = info.channels;
  switch (info.accumulation) {
    case Accumulation::FilteredAverage:
      if (!p.weight.is_zero()) {
        average(s, n, weight, out);
      } else {
        for (int c = 0; c < n; ++c) out[c] = 0.0f;
      }
      // A reflectance: a filter's negative lobes must not make it negative.
      if (info.type == AovType::Albedo)
        for (int c = 0; c < 3; ++c) out[c] = std::max(out[c], 0.0f);
      break;
    case Accumulation::Ranked: {
      const int ranks = aovs_[layer].ranks;
      ranked_values(s, ranks, p.weight, out);
      for (int c = 2 * ranks; c < channel_count_[layer]; ++c) out[c] = 0.0f;  // an odd rank's last pair
      break;
    }
    case Accumulation::FirstSample:
      for (int c = 0; c < n; ++c) out[c] = static_cast<float>(d[c]);
      break;
    case Accumulation::Sum:
      if (info.type == AovType::Samples) {
        out[0] = static_cast<float>(p.samples);
      } else if (p.samples >= 2) {  // variance of the mean: unbiased sample variance / n
        const double count = static_cast<double>(p.samples);
        for (int c = 0; c < 3; ++c) {
          const double sum = s[c].value(), mean = sum / count;
          const double var = std::max(0.0, (s[3 + c].value() - sum * mean) / (count - 1.0));
          out[c] = static_cast<float>(var / count);
        }
      } else {
        for (int c = 0; c < channel_count_[layer]; ++c) out[c] = 0.0f;
      }
      break;
    case Accumulation::Max:
      out[0] = static_cast<float>(d[0]);
      break;
  }
}

std::vector<float> Film::aov_value(AovType type, int x, int y) const {
  for (std::size_t i = 0; i < aovs_.size(); ++i) {
    if (aovs_[i].type != type) continue;
    std::vector<float> out(static_cast<std::size_t>(aov_channel_count(aovs_[i])));
    aov_values(i, index(x, y), out.data());
    return out;
  }
  return {};
}

LayeredImage Film::layer_layout(ChannelType beauty_type, const PixelRect& window) const {
  LayeredImage out;
  out.full_width = width_;
  out.full_height = height_;
  out.x = window.x0;
  out.y = window.y0;
  out.width = window.width();
  out.height = window.height();
  const std::size_t n = out.pixel_count();
  out.layers.push_back({"", {"R", "G", "B", "A"}, beauty_type, std::vector<float>(n * 4)});
  // A Ranked AOV is a layer per two ranks ("CryptoObject00": r, g, b, a); any other one layer.
  for (const AovRequest& r : aovs_) {
    const std::vector<std::string> names = aov_channel_names(r);
    const std::size_t nc = names.size(), per_layer = aov_info(r.type).accumulation == Accumulation::Ranked ? 4 : nc;
    for (std::size_t first = 0; first < nc; first += per_layer) {
      const auto from = names.begin() + static_cast<std::ptrdiff_t>(first);
      out.layers.push_back({names[first].substr(0, names[first].find('.')), {from, from + static_cast<std::ptrdiff_t>(per_layer)},
                            r.channel_type, std::vector<float>(n * per_layer)});
    }
  }
  return out;
}

std::size_t Film::resolved_channels() const {
  std::size_t n = 4;
  for (const int c : channel_count_) n += static_cast<std::size_t>(c);
  return n;
}

void Film::resolve_pixel(std::size_t pixel, float* out) const {
  const PixelSum& p = pixels_[pixel];
  const RGB v = p.value();
  out[0] = v.r;
  out[1] = v.g;
  out[2] = v.b;
  out[3] = p.alpha();
  out += 4;
  // Each AOV's channels follow the beauty in request order, as its layers do
  // (layer_layout): the filtered averages (aov_values') a run at a time.
  const double weight = p.weight.is_zero() ? 0.0 : p.weight.value();
  const ExactSum* s = aov_sums_.data() + pixel * static_cast<std::size_t>(sum_stride_);
  const double* d = aov_values_.data() + pixel * static_cast<std::size_t>(value_stride_);
  float* const channels = out - 4;
  for (std::size_t l = 0; l < aovs_.size(); ++l) {
    if (averaged_[l] == 0)
      aov_values(l, p, weight, s + sum_offset_[l], d + value_offset_[l], out);
    out += channel_count_[l];
  }
  for (const AverageRun& run : average_runs_) {
    if (!p.weight.is_zero()) {
      average(s + run.sum, run.count, weight, channels + run.out);
    } else {
      std::fill_n(channels + run.out, run.count, 0.0f);
    }
  }
  // A reflectance: a filter's negative lobes must not make it negative (as aov_values).
  if (albedo_out_ >= 0)
    for (int c = 0; c < 3; ++c) channels[albedo_out_ + c] = std::max(channels[albedo_out_ + c], 0.0f);
}

void Film::resolve_channels(std::size_t first, std::size_t count, float* out) const {
  const std::size_t n = resolved_channels();
  for (std::size_t i = 0; i < count; ++i) resolve_pixel(first + i, out + i * n);
}

void Film::resolve_pixels(LayeredImage& out, std::size_t first, std::size_t count, std::size_t at) const {
  std::vector<float> values(resolved_channels());
  for (std::size_t i = first; i < first + count; ++i, ++at) {
    resolve_pixel(i, values.data());
    const float* v = values.data();
    for (ImageLayer& layer : out.layers) {
      const std::size_t n = layer.channels.size();
      std::copy_n(v, n, &layer.values[at * n]);
      v += n;
    }
  }
}

void Film::resolve_into(LayeredImage& out) const {
  const std::size_t at = static_cast<std::size_t>(crop_.y0 - out.y) * static_cast<std::size_t>(out.width) +
                         static_cast<std::size_t>(crop_.x0 - out.x);
  resolve_pixels(out, 0, pixels_.size(), at);
}

LayeredImage Film::layers(ChannelType beauty_type) const {
  LayeredImage out = layer_layout(beauty_type, crop_);
  // Every pixel is resolved alone, so rows in parallel give the same bits; the
  // tasks run with the caller's floating-point settings (as a loop here would).
  tbb::task_group_context context;
  context.capture_fp_settings();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.pixel_count(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
    resolve_pixels(out, range.begin(), range.size(), range.begin());
  }, tbb::auto_partitioner(), context);
  return out;
}

void Film::recrop(const PixelRect& crop) {
  move_to(crop);
  clear();
}

void Film::move_to(const PixelRect& crop) {
  crop_ = clip(crop, width_, height_);
  const std::size_t n = static_cast<std::size_t>(crop_.width()) * static_cast<std::size_t>(crop_.height());
  pixels_.resize(n);  // within the capacity of a film of that size or larger: no allocation
  aov_sums_.resize(n * static_cast<std::size_t>(sum_stride_));
  aov_values_.resize(n * static_cast<std::size_t>(value_stride_));
  non_finite_ = {};
}

}  // namespace pt
