#include "render/film/film.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <sstream>
#include <tuple>

namespace pt {

namespace {

PixelRect clip(PixelRect r, int width, int height) {
  r.x0 = std::clamp(r.x0, 0, width);
  r.x1 = std::clamp(r.x1, r.x0, width);
  r.y0 = std::clamp(r.y0, 0, height);
  r.y1 = std::clamp(r.y1, r.y0, height);
  return r;
}

void add_weighted(double* s, float w, float a, float b, float c) {
  s[0] += static_cast<double>(w) * a;
  s[1] += static_cast<double>(w) * b;
  s[2] += static_cast<double>(w) * c;
}

void add_weighted(double* s, float w, RGB v) { add_weighted(s, w, v.r, v.g, v.b); }

// First-sample layers: n values and a flag (1 once set).
void set_first(double* s, int n, const float* v) {
  if (s[n] != 0.0) return;
  for (int c = 0; c < n; ++c) s[c] = v[c];
  s[n] = 1.0;
}

// Ranked (Cryptomatte) layers: `ranks` slots of (id, weight sum); id 0 marks
// a free slot (no name hashes to 0). A weight goes to its id's slot, else to
// the first free one; when every slot holds another id it is dropped (as
// Cycles does), so the ids kept are the first `ranks` distinct ones in sample
// order, and the result does not depend on scheduling.
void add_ranked(double* slots, int ranks, double id, double w) {
  if (id == 0.0) return;  // the camera ray hit nothing
  for (int k = 0; k < ranks; ++k) {
    double* slot = slots + 2 * k;
    if (slot[0] == id) {
      slot[1] += w;
      return;
    }
    if (slot[0] == 0.0) {
      slot[0] = id;
      slot[1] = w;
      return;
    }
  }
}

// The ranked ids and coverages (weight / the pixel's total weight, clamped
// to [0, 1]) into out[0 .. 2 * ranks), highest coverage first (ties: the
// smaller id first); free slots give (0, 0).
void ranked_values(const double* slots, int ranks, double weight, float* out) {
  std::array<int, kCryptomatteMaxRanks> order{};
  for (int k = 0; k < ranks; ++k) order[static_cast<std::size_t>(k)] = k;
  const auto key = [slots](int k) { return std::make_pair(slots[2 * k] == 0.0, -slots[2 * k + 1]); };
  std::sort(order.begin(), order.begin() + ranks, [&](int a, int b) {
    return key(a) != key(b) ? key(a) < key(b) : slots[2 * a] < slots[2 * b];
  });
  for (int k = 0; k < ranks; ++k) {
    const double* slot = slots + 2 * order[static_cast<std::size_t>(k)];
    const bool used = slot[0] != 0.0 && weight != 0.0;
    out[2 * k] = used ? static_cast<float>(slot[0]) : 0.0f;
    out[2 * k + 1] = used ? static_cast<float>(std::clamp(slot[1] / weight, 0.0, 1.0)) : 0.0f;
  }
}

}  // namespace

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
  for (AovRequest& r : aovs_) {
    const AovInfo& info = aov_info(r.type);
    r.ranks = info.accumulation != Accumulation::Ranked ? 0
              : r.ranks <= 0                             ? kCryptomatteDefaultRanks
                                                         : std::min(r.ranks, kCryptomatteMaxRanks);
    offset_.push_back(stride_);
    stride_ += aov_state_doubles(r);
    if (aov_bit(r.type) & kGeometryAovs) wants_geometry_ = true;
    if (info.lighting) wants_lighting_ = true;
  }
  aov_data_.assign(pixels_.size() * static_cast<std::size_t>(stride_), 0.0);
}

Image Film::image() const {
  Image out(crop_.width(), crop_.height());
  for (std::size_t i = 0; i < pixels_.size(); ++i) out.pixels[i] = pixels_[i].value();
  return out;
}

void Film::clear() {
  std::fill(pixels_.begin(), pixels_.end(), PixelSum{});
  std::fill(aov_data_.begin(), aov_data_.end(), 0.0);
  non_finite_ = {};
}

void Film::accumulate(double* scratch, const AovSample& a, RGB radiance, float w, bool non_finite) const {
  for (std::size_t i = 0; i < aovs_.size(); ++i) {
    double* s = scratch + offset_[i];
    switch (aovs_[i].type) {
      case AovType::Albedo: add_weighted(s, w, a.albedo); break;
      case AovType::Normal: add_weighted(s, w, a.normal.x, a.normal.y, a.normal.z); break;
      case AovType::Position: {
        const float v[3] = {a.position.x, a.position.y, a.position.z};
        set_first(s, 3, v);
        break;
      }
      case AovType::Depth: set_first(s, 1, &a.depth); break;
      case AovType::ObjectId: {
        const float v = static_cast<float>(a.object);
        set_first(s, 1, &v);
        break;
      }
      case AovType::MaterialId: {
        const float v = static_cast<float>(a.material);
        set_first(s, 1, &v);
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
            const double v = radiance[c];
            s[c] += v;
            s[3 + c] += v * v;
          }
        }
        break;
      case AovType::Samples: break;  // the beauty's count
      case AovType::NonFinite: if (non_finite) s[0] = 1.0; break;
      case AovType::CryptoObject: add_ranked(s, aovs_[i].ranks, a.crypto_object, w); break;
      case AovType::CryptoMaterial: add_ranked(s, aovs_[i].ranks, a.crypto_material, w); break;
    }
  }
}

void Film::add_aovs(int x, int y, const double* scratch) {
  double* film = aov_data_.data() + index(x, y) * static_cast<std::size_t>(stride_);
  for (std::size_t i = 0; i < aovs_.size(); ++i) {
    const AovInfo& info = aov_info(aovs_[i].type);
    double* d = film + offset_[i];
    const double* s = scratch + offset_[i];
    switch (info.accumulation) {
      case Accumulation::FilteredAverage:
      case Accumulation::Sum:
        for (int c = 0; c < info.state_doubles; ++c) d[c] += s[c];
        break;
      case Accumulation::FirstSample:
        if (d[info.channels] == 0.0 && s[info.channels] != 0.0)
          std::copy(s, s + info.state_doubles, d);
        break;
      case Accumulation::Max:
        d[0] = std::max(d[0], s[0]);
        break;
      case Accumulation::Ranked:
        for (int k = 0; k < aovs_[i].ranks; ++k) add_ranked(d, aovs_[i].ranks, s[2 * k], s[2 * k + 1]);
        break;
    }
  }
}

void Film::aov_values(std::size_t layer, std::size_t pixel, float* out) const {
  const AovType type = aovs_[layer].type;
  const AovInfo& info = aov_info(type);
  const double* d = aov_data_.data() + pixel * static_cast<std::size_t>(stride_) + offset_[layer];
  const PixelSum& p = pixels_[pixel];
  std::fill(out, out + aov_channel_count(aovs_[layer]), 0.0f);
  switch (info.accumulation) {
    case Accumulation::FilteredAverage:
      if (p.weight != 0.0)
        for (int c = 0; c < info.channels; ++c) out[c] = static_cast<float>(d[c] / p.weight);
      // A reflectance: a filter's negative lobes must not make it negative.
      if (type == AovType::Albedo)
        for (int c = 0; c < 3; ++c) out[c] = std::max(out[c], 0.0f);
      break;
    case Accumulation::Ranked:
      ranked_values(d, aovs_[layer].ranks, p.weight, out);
      break;
    case Accumulation::FirstSample:
      for (int c = 0; c < info.channels; ++c) out[c] = static_cast<float>(d[c]);
      break;
    case Accumulation::Sum:
      if (type == AovType::Samples) {
        out[0] = static_cast<float>(p.samples);
      } else if (p.samples >= 2) {  // variance of the mean: unbiased sample variance / n
        const double n = static_cast<double>(p.samples);
        for (int c = 0; c < 3; ++c) {
          const double mean = d[c] / n;
          const double var = std::max(0.0, (d[3 + c] - d[c] * mean) / (n - 1.0));
          out[c] = static_cast<float>(var / n);
        }
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

LayeredImage Film::layers(ChannelType beauty_type) const {
  LayeredImage out;
  out.full_width = width_;
  out.full_height = height_;
  out.x = crop_.x0;
  out.y = crop_.y0;
  out.width = crop_.width();
  out.height = crop_.height();
  const std::size_t n = out.pixel_count();
  ImageLayer beauty{"", {"R", "G", "B", "A"}, beauty_type, std::vector<float>(n * 4)};
  for (std::size_t i = 0; i < n; ++i) {
    const RGB v = pixels_[i].value();
    float* p = &beauty.values[i * 4];
    p[0] = v.r;
    p[1] = v.g;
    p[2] = v.b;
    p[3] = pixels_[i].alpha();
  }
  out.layers.push_back(std::move(beauty));
  for (std::size_t l = 0; l < aovs_.size(); ++l) {
    const AovRequest& r = aovs_[l];
    const std::vector<std::string> names = aov_channel_names(r);
    const std::size_t nc = names.size();
    std::vector<float> values(n * nc);
    for (std::size_t i = 0; i < n; ++i) aov_values(l, i, &values[i * nc]);
    // A Ranked AOV is a layer per two ranks ("CryptoObject00": r, g, b, a); any other one layer.
    const std::size_t per_layer = aov_info(r.type).accumulation == Accumulation::Ranked ? 4 : nc;
    for (std::size_t first = 0; first < nc; first += per_layer) {
      ImageLayer layer;
      layer.name = names[first].substr(0, names[first].find('.'));
      layer.type = r.channel_type;
      layer.channels.assign(names.begin() + static_cast<std::ptrdiff_t>(first),
                            names.begin() + static_cast<std::ptrdiff_t>(first + per_layer));
      layer.values.resize(n * per_layer);
      for (std::size_t i = 0; i < n; ++i)
        std::copy_n(&values[i * nc + first], per_layer, &layer.values[i * per_layer]);
      out.layers.push_back(std::move(layer));
    }
  }
  return out;
}

}  // namespace pt
