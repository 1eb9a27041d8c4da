// Film::write_state / read_state: checkpoints of a film, bit for bit.
#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cmath>
#include <cstring>
#include <istream>
#include <ostream>
#include <string_view>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/memory_stream.h"
#include "render/film/film.h"

namespace pt {

namespace {

// State layout (version 4), all little-endian:
//   the 8-byte magic; uint32 version, width, height; int32 crop x0, y0, x1, y1;
//   uint32 AOV count, then per AOV uint8 type, uint8 channel type and uint8
//   ranks (Cryptomatte; 0 for the others);
//   the non-finite report: uint64 nan, pos_inf, neg_inf; uint8 has_first;
//   int32 x, y, sample; float r, g, b;
//   per pixel of the crop (row-major, top row first): r, g, b, weight,
//   coverage as exact sums (render/film/exact_sum.h: 128-bit two's-complement
//   integers, the low 64 bits first, in units of 2^-44) and samples as uint64;
//   then the AOVs' exact sums: per pixel, their sums in request order (a
//   Cryptomatte layer: per rank, its id's 32 bits as the integer and its weight);
//   then the AOVs' plain values: per pixel, their values as IEEE doubles.
// Versions 1 (beauty only, no crop), 2 (sums in double) and 3 (either sums in
// double with coverage, or exact sums without it) are no longer read.
constexpr char kMagic[8] = {'P', 'T', 'F', 'I', 'L', 'M', '\r', '\n'};
constexpr uint32_t kStateVersion = 4;
static_assert(std::endian::native == std::endian::little, "film states are written in the host's byte order");

template <typename T>
void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
bool get(std::istream& in, T& v) {
  return static_cast<bool>(in.read(reinterpret_cast<char*>(&v), sizeof v));
}

// A vector of trivially copyable elements, as in memory.
template <typename T>
void put_all(std::ostream& out, const std::vector<T>& v) {
  const auto bytes = static_cast<std::streamsize>(v.size() * sizeof(T));
  if (!v.empty()) out.write(reinterpret_cast<const char*>(v.data()), bytes);
}
template <typename T>
bool get_all(std::istream& in, std::vector<T>& v) {
  const auto bytes = static_cast<std::streamsize>(v.size() * sizeof(T));
  return v.empty() || static_cast<bool>(in.read(reinterpret_cast<char*>(v.data()), bytes));
}

std::string describe_aovs(const std::vector<AovRequest>& aovs) {
  if (aovs.empty()) return "none";
  std::string s;
  for (const AovRequest& r : aovs) {
    if (!s.empty()) s += ',';
    s += aov_info(r.type).name;
    s += r.channel_type == ChannelType::Half ? ":half" : ":float";
    if (r.ranks > 0) s += " (" + std::to_string(r.ranks) + " ranks)";
  }
  return s;
}

// The AOV list of `count` entries; false with `error` unless it is `expected`.
bool read_aov_list(std::istream& in, uint32_t count, const std::vector<AovRequest>& expected, std::string& error) {
  if (count > aov_catalogue().size()) {
    error = "film state lists " + std::to_string(count) + " AOVs (corrupt)";
    return false;
  }
  std::vector<AovRequest> aovs;
  for (uint32_t i = 0; i < count; ++i) {
    uint8_t type = 0, channel_type = 0, ranks = 0;
    if (!get(in, type) || !get(in, channel_type) || !get(in, ranks)) {
      error = "truncated film state header";
      return false;
    }
    if (type >= aov_catalogue().size() || channel_type > 1 || ranks > kCryptomatteMaxRanks) {
      error = "film state lists an unknown AOV (corrupt)";
      return false;
    }
    aovs.push_back({static_cast<AovType>(type), static_cast<ChannelType>(channel_type), ranks});
  }
  const auto same = [](const AovRequest& a, const AovRequest& b) {
    return a.type == b.type && a.channel_type == b.channel_type && a.ranks == b.ranks;
  };
  if (!std::equal(aovs.begin(), aovs.end(), expected.begin(), expected.end(), same)) {
    error = "film state has AOVs " + describe_aovs(aovs) + ", the render asks for " + describe_aovs(expected);
    return false;
  }
  return true;
}

// The header up to the AOV list; false with `error` unless it describes a
// film of this size and AOVs. `crop` is the state's.
bool read_layout(std::istream& in, int width, int height, PixelRect& crop, const std::vector<AovRequest>& expected,
                 std::string& error) {
  char magic[sizeof kMagic];
  uint32_t version = 0, w = 0, h = 0;
  if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0) {
    error = "not a film state (bad magic)";
    return false;
  }
  if (!get(in, version) || version != kStateVersion) {
    error = "unsupported film state version " + std::to_string(version) + " (expected " +
            std::to_string(kStateVersion) + ")";
    return false;
  }
  int32_t c[4];
  uint32_t count = 0;
  if (!get(in, w) || !get(in, h) || !get(in, c[0]) || !get(in, c[1]) || !get(in, c[2]) || !get(in, c[3]) ||
      !get(in, count)) {
    error = "truncated film state header";
    return false;
  }
  if (static_cast<int64_t>(w) != width || static_cast<int64_t>(h) != height) {
    error = "film state is " + std::to_string(w) + "x" + std::to_string(h) + ", the render is " +
            std::to_string(width) + "x" + std::to_string(height);
    return false;
  }
  crop = {c[0], c[1], c[2], c[3]};
  return read_aov_list(in, count, expected, error);
}

bool read_non_finite(std::istream& in, NonFiniteReport& nf, std::string& error) {
  uint8_t has_first = 0;
  int32_t fx = 0, fy = 0, fs = 0;
  if (!get(in, nf.nan) || !get(in, nf.pos_inf) || !get(in, nf.neg_inf) || !get(in, has_first) || !get(in, fx) ||
      !get(in, fy) || !get(in, fs) || !get(in, nf.value.r) || !get(in, nf.value.g) || !get(in, nf.value.b)) {
    error = "truncated film state header";
    return false;
  }
  if (has_first > 1) {  // written as 0 or 1: anything else is corruption (found by fuzz_film_state)
    error = "corrupt film state (non-finite report flag " + std::to_string(has_first) + ")";
    return false;
  }
  nf.has_first = has_first == 1;
  nf.x = fx;
  nf.y = fy;
  nf.sample = fs;
  return true;
}

// Reads `items` groups of `per_item` values of T in blocks of about 8 MiB,
// calling `add(block, first_item, item_count)` for each; false if the stream
// ends first or `add` refuses.
template <typename T, typename F>
bool read_blocks(std::istream& in, std::size_t items, std::size_t per_item, F&& add) {
  if (per_item == 0) return true;
  const std::size_t per_block = std::max<std::size_t>(1, (std::size_t{8} << 20) / (sizeof(T) * per_item));
  std::vector<T> block(std::min(items, per_block) * per_item);
  for (std::size_t first = 0; first < items; first += per_block) {
    const std::size_t n = std::min(per_block, items - first);
    if (!in.read(reinterpret_cast<char*>(block.data()), static_cast<std::streamsize>(n * per_item * sizeof(T))) ||
        !add(block.data(), first, n))
      return false;
  }
  return true;
}

}  // namespace

bool Film::write_state(std::ostream& out) const {
  out.write(kMagic, sizeof kMagic);
  put(out, kStateVersion);
  put(out, static_cast<uint32_t>(width_));
  put(out, static_cast<uint32_t>(height_));
  for (int v : {crop_.x0, crop_.y0, crop_.x1, crop_.y1}) put(out, static_cast<int32_t>(v));
  put(out, static_cast<uint32_t>(aovs_.size()));
  for (const AovRequest& r : aovs_) {
    put(out, static_cast<uint8_t>(r.type));
    put(out, static_cast<uint8_t>(r.channel_type));
    put(out, static_cast<uint8_t>(r.ranks));
  }
  const NonFiniteReport& nf = non_finite_;
  put(out, nf.nan);
  put(out, nf.pos_inf);
  put(out, nf.neg_inf);
  put(out, static_cast<uint8_t>(nf.has_first));
  for (int v : {nf.x, nf.y, nf.sample}) put(out, static_cast<int32_t>(v));
  for (float v : {nf.value.r, nf.value.g, nf.value.b}) put(out, v);
  put_all(out, pixels_);
  put_all(out, aov_sums_);
  put_all(out, aov_values_);
  return static_cast<bool>(out);
}

bool Film::read_state(std::istream& in, std::string& error) {
  PixelRect crop;
  if (!read_layout(in, width_, height_, crop, aovs_, error)) return false;
  if (crop != crop_) {
    error = "film state covers pixels " + crop.text() + ", the render's crop is " + crop_.text();
    return false;
  }
  NonFiniteReport nf;
  if (!read_non_finite(in, nf, error)) return false;
  // Integer sums cannot be corrupt in value (any bits are some sum); the
  // samples are checked against the header by the checkpoint and shard readers.
  std::vector<PixelSum> pixels(pixels_.size());
  std::vector<ExactSum> sums(aov_sums_.size());
  std::vector<double> values(aov_values_.size());
  if (!get_all(in, pixels) || !get_all(in, sums) || !get_all(in, values)) {
    error = "truncated film state";
    return false;
  }
  if (in.peek() != std::char_traits<char>::eof()) {
    error = "film state has trailing data";
    return false;
  }
  const auto stride = static_cast<std::size_t>(sum_stride_);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    if (!valid_ranked(sums.data() + i * stride)) {
      error = "corrupt film state (Cryptomatte slots of pixel " + std::to_string(i) + " of the crop)";
      return false;
    }
  pixels_ = std::move(pixels);
  aov_sums_ = std::move(sums);
  aov_values_ = std::move(values);
  non_finite_ = nf;
  return true;
}

namespace {

// The header of a film state to add (add_state): its layout and crop checked
// against `rules`, its non-finite report into `nf`. False with `error`.
bool read_added_header(std::istream& in, int width, int height, const PixelRect& film_crop,
                       const std::vector<AovRequest>& aovs, const StateRules& rules, NonFiniteReport& nf,
                       std::string& error) {
  PixelRect c;
  if (!read_layout(in, width, height, c, aovs, error)) return false;
  if (c != rules.crop || !film_crop.contains(c)) {
    error = "film state covers pixels " + c.text() + ", not " + rules.crop.text() + " inside " + film_crop.text();
    return false;
  }
  if (!read_non_finite(in, nf, error)) return false;
  const std::size_t n = static_cast<std::size_t>(c.width()) * static_cast<std::size_t>(c.height());
  if (rules.other_first.size() != n || rules.max_samples.size() != n) {
    error = "film state rules of the wrong size";
    return false;
  }
  return true;
}

// Pixels per block of the parallel add (about 4 MiB of state with every AOV).
constexpr std::size_t kAddGrain = 4096;

// Runs `add(first, count)` over [0, items) in blocks, in parallel (in the
// caller's TBB arena); the smallest of the blocks' answers (a pixel number,
// or `items` for none).
template <typename F>
std::size_t for_blocks(std::size_t items, F&& add) {
  std::atomic<std::size_t> lowest{items};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items, kAddGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    const std::size_t found = add(r.begin(), r.size());
    std::size_t seen = lowest.load();
    while (found < seen && !lowest.compare_exchange_weak(seen, found)) {
    }
  });
  return lowest.load();
}

}  // namespace

// The state's bytes need not be aligned (a mapped shard file: its header's
// length varies), so each pixel's values are copied out (memcpy: unaligned
// loads) before they are added.
std::size_t Film::add_state_pixels(const char* p, std::size_t first, std::size_t count, const StateRules& rules) {
  const auto width = static_cast<std::size_t>(rules.crop.width());
  for (std::size_t i = first; i < first + count; ++i) {
    PixelSum sum;
    std::memcpy(&sum, p + (i - first) * sizeof sum, sizeof sum);
    if (sum.samples > rules.max_samples[i - rules.first]) return i;
    pixels_[index(rules.crop.x0 + static_cast<int>(i % width), rules.crop.y0 + static_cast<int>(i / width))].add(sum);
  }
  return SIZE_MAX;
}

std::size_t Film::add_state_sums(const char* s, std::size_t first, std::size_t count, const StateRules& rules) {
  const auto width = static_cast<std::size_t>(rules.crop.width());
  std::vector<ExactSum> sums(static_cast<std::size_t>(sum_stride_));
  const std::size_t bytes = sums.size() * sizeof(ExactSum);
  for (std::size_t i = first; i < first + count; ++i) {
    std::memcpy(static_cast<void*>(sums.data()), s + (i - first) * bytes, bytes);
    if (!valid_ranked(sums.data())) return i;
    add_sums(index(rules.crop.x0 + static_cast<int>(i % width), rules.crop.y0 + static_cast<int>(i / width)),
             sums.data());
  }
  return SIZE_MAX;
}

void Film::add_state_values(const char* v, std::size_t first, std::size_t count, const StateRules& rules) {
  const auto width = static_cast<std::size_t>(rules.crop.width());
  std::vector<double> values(static_cast<std::size_t>(value_stride_));
  const std::size_t bytes = values.size() * sizeof(double);
  for (std::size_t i = first; i < first + count; ++i) {
    std::memcpy(values.data(), v + (i - first) * bytes, bytes);
    add_values(index(rules.crop.x0 + static_cast<int>(i % width), rules.crop.y0 + static_cast<int>(i / width)),
               values.data(), rules.other_first[i - rules.first] != 0);
  }
}

std::string Film::too_many_samples(std::size_t pixel, uint64_t samples, const StateRules& rules) {
  const auto width = static_cast<std::size_t>(rules.crop.width());
  return "its film state holds " + std::to_string(samples) + " samples in pixel (" +
         std::to_string(rules.crop.x0 + static_cast<int>(pixel % width)) + ", " +
         std::to_string(rules.crop.y0 + static_cast<int>(pixel / width)) + "), more than its pieces' " +
         std::to_string(rules.max_samples[pixel - rules.first]) + " (the two do not belong together)";
}

bool Film::add_state(std::istream& in, const StateRules& rules, std::string& error) {
  NonFiniteReport nf;
  if (!read_added_header(in, width_, height_, crop_, aovs_, rules, nf, error)) return false;
  const std::size_t n = rules.max_samples.size();
  std::size_t bad = SIZE_MAX;  // the first pixel with too many samples, and its count
  uint64_t bad_samples = 0;
  const bool pixels_ok = read_blocks<PixelSum>(in, n, 1, [&](const PixelSum* p, std::size_t first, std::size_t count) {
    bad = add_state_pixels(reinterpret_cast<const char*>(p), first, count, rules);
    if (bad != SIZE_MAX) bad_samples = p[bad - first].samples;
    return bad == SIZE_MAX;
  });
  if (bad != SIZE_MAX) {
    error = too_many_samples(bad, bad_samples, rules);
    return false;
  }
  const auto sums = static_cast<std::size_t>(sum_stride_), values = static_cast<std::size_t>(value_stride_);
  bool corrupt = false;
  const bool ok =
      pixels_ok &&
      read_blocks<ExactSum>(in, n, sums, [&](const ExactSum* s, std::size_t first, std::size_t count) {
        corrupt = add_state_sums(reinterpret_cast<const char*>(s), first, count, rules) != SIZE_MAX;
        return !corrupt;
      }) &&
      read_blocks<double>(in, n, values, [&](const double* v, std::size_t first, std::size_t count) {
        add_state_values(reinterpret_cast<const char*>(v), first, count, rules);
        return true;
      });
  if (!ok) {
    error = corrupt ? "corrupt film state (Cryptomatte slots)" : "truncated film state";
    return false;
  }
  if (in.peek() != std::char_traits<char>::eof()) {
    error = "film state has trailing data";
    return false;
  }
  non_finite_.merge(nf);
  return true;
}

bool Film::view_state(std::string_view state, const PixelRect& crop, const PixelRect& inside, StateView& view,
                      std::string& error) const {
  MemoryBuffer buffer(state);
  std::istream in(&buffer);
  PixelRect c;
  if (!read_layout(in, width_, height_, c, aovs_, error)) return false;
  if (c != crop || !inside.contains(c)) {
    error = "film state covers pixels " + c.text() + ", not " + crop.text() + " inside " + inside.text();
    return false;
  }
  if (!read_non_finite(in, view.non_finite, error)) return false;
  // The whole body is checked for its size before any of it is added.
  const std::size_t n = static_cast<std::size_t>(c.width()) * static_cast<std::size_t>(c.height());
  const std::size_t header = buffer.consumed();
  const auto sums = static_cast<std::size_t>(sum_stride_), values = static_cast<std::size_t>(value_stride_);
  const std::size_t body = n * (sizeof(PixelSum) + sums * sizeof(ExactSum) + values * sizeof(double));
  if (state.size() - header != body) {
    error = state.size() - header < body ? "truncated film state" : "film state has trailing data";
    return false;
  }
  view.crop = c;
  view.pixels = state.data() + header;
  view.sums = view.pixels + n * sizeof(PixelSum);
  view.values = view.sums + n * sums * sizeof(ExactSum);
  return true;
}

std::string Film::refusal(const StateView& view, std::size_t pixel, const StateRules& rules) {
  PixelSum sum;
  std::memcpy(&sum, view.pixels + pixel * sizeof sum, sizeof sum);
  if (sum.samples > rules.max_samples[pixel - rules.first]) return too_many_samples(pixel, sum.samples, rules);
  return "corrupt film state (Cryptomatte slots)";
}

std::size_t Film::add_state_rows(const StateView& view, const StateRules& rules, int y0, int y1) {
  const auto width = static_cast<std::size_t>(view.crop.width());
  const std::size_t first = static_cast<std::size_t>(y0 - view.crop.y0) * width;
  const std::size_t count = static_cast<std::size_t>(y1 - y0) * width;
  const std::size_t sum_bytes = static_cast<std::size_t>(sum_stride_) * sizeof(ExactSum);
  const std::size_t value_bytes = static_cast<std::size_t>(value_stride_) * sizeof(double);
  if (const std::size_t bad = add_state_pixels(view.pixels + first * sizeof(PixelSum), first, count, rules);
      bad != SIZE_MAX)
    return bad;
  if (sum_stride_ > 0)
    if (const std::size_t bad = add_state_sums(view.sums + first * sum_bytes, first, count, rules); bad != SIZE_MAX)
      return bad;
  if (value_stride_ > 0) add_state_values(view.values + first * value_bytes, first, count, rules);
  return SIZE_MAX;
}

bool Film::add_state(std::string_view state, const StateRules& rules, std::string& error) {
  StateView view;
  if (!view_state(state, rules.crop, crop_, view, error)) return false;
  const std::size_t n = rules.max_samples.size();
  if (rules.first != 0 || rules.other_first.size() != n ||
      n != static_cast<std::size_t>(view.crop.width()) * static_cast<std::size_t>(view.crop.height())) {
    error = "film state rules of the wrong size";
    return false;
  }
  const auto sums = static_cast<std::size_t>(sum_stride_), values = static_cast<std::size_t>(value_stride_);
  const std::size_t sum_bytes = sums * sizeof(ExactSum), value_bytes = values * sizeof(double);
  const std::size_t bad = for_blocks(n, [&](std::size_t first, std::size_t count) {
    return std::min(n, add_state_pixels(view.pixels + first * sizeof(PixelSum), first, count, rules));
  });
  if (bad < n) {
    error = refusal(view, bad, rules);
    return false;
  }
  if (sums > 0 && for_blocks(n, [&](std::size_t first, std::size_t count) {
        return std::min(n, add_state_sums(view.sums + first * sum_bytes, first, count, rules));
      }) < n) {
    error = "corrupt film state (Cryptomatte slots)";
    return false;
  }
  if (values > 0)
    for_blocks(n, [&](std::size_t first, std::size_t count) {
      add_state_values(view.values + first * value_bytes, first, count, rules);
      return n;
    });
  non_finite_.merge(view.non_finite);
  return true;
}

}  // namespace pt
