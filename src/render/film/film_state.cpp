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

// State layout (version 5), all little-endian:
//   the 8-byte magic; uint32 version, width, height; int32 crop x0, y0, x1, y1;
//   uint32 AOV count, then per AOV uint8 type, uint8 channel type and uint8
//   ranks (Cryptomatte; 0 for the others);
//   the non-finite report: uint64 nan, pos_inf, neg_inf; uint8 has_first;
//   int32 x, y, sample; float r, g, b;
//   uint64 the number of exceptions, then each: uint64 pixel (of the crop,
//   row-major), uint32 slot, its value as 128 bits (the low 64 first), in
//   increasing (pixel, slot) order;
//   per pixel of the crop (row-major, top row first), its record
//   (film_state_codec.cpp): r, g, b, weight and coverage as int64 (exact sums,
//   render/film/exact_sum.h: integers in units of 2^-44), samples as uint32,
//   the AOVs' exact sums in request order as int64 (a Cryptomatte layer: per
//   rank, its id's 32 bits as uint32 and its weight as int64), then the AOVs'
//   plain values as floats. A slot whose value its type cannot hold is 0 in
//   the record and listed among the exceptions with its full value (a sum's
//   128-bit integer, the count, a value's double bits).
// Versions 1 (beauty only, no crop), 2 (sums in double), 3 (either sums in
// double with coverage, or exact sums without it) and 4 (every sum in 128
// bits, values in double: 992 bytes a pixel with every AOV, 448 now) are no
// longer read.
constexpr char kMagic[8] = {'P', 'T', 'F', 'I', 'L', 'M', '\r', '\n'};
constexpr uint32_t kStateVersion = 5;
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
  if (!get(in, version)) {
    error = "truncated film state header";
    return false;
  }
  if (version != kStateVersion) {
    error = "film state version " + std::to_string(version) + " is not read by this pathtracer, which reads version " +
            std::to_string(kStateVersion) +
            (version < kStateVersion ? " (written by an older one: render it again with this one)" : "");
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


namespace {

// Pixels per block of the parallel encode and add (under 2 MiB of records
// with every AOV).
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

// Runs `f(block, first, count)` for blocks [block * kAddGrain, ...) of
// [0, items), in parallel.
template <typename F>
void for_each_block(std::size_t items, F&& f) {
  const std::size_t blocks = (items + kAddGrain - 1) / kAddGrain;
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    f(b, b * kAddGrain, std::min(kAddGrain, items - b * kAddGrain));
  });
}

// Asks for the record `ahead` records after `record` (of `bytes`) to be
// brought into the cache: a state's records stream from a mapped file, whose
// pages the hardware prefetcher does not cross.
constexpr std::size_t kPrefetchRecords = 4;
inline void prefetch_record(const char* record, std::size_t bytes) {
  const char* ahead = record + kPrefetchRecords * bytes;
  for (std::size_t at = 0; at < bytes; at += 64) __builtin_prefetch(ahead + at);
}

// The exceptions of pixel `pixel` onwards: the first of them.
const StateException* exceptions_from(const std::vector<StateException>& ex, std::size_t pixel) {
  return ex.data() + (std::lower_bound(ex.begin(), ex.end(), pixel,
                                       [](const StateException& e, std::size_t p) { return e.pixel < p; }) -
                      ex.begin());
}
// The end of pixel `pixel`'s exceptions, which begin at `from`.
const StateException* exceptions_end(const std::vector<StateException>& ex, const StateException* from,
                                     std::size_t pixel) {
  const StateException* end = ex.data() + ex.size();
  while (from != end && from->pixel == pixel) ++from;
  return from;
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
  // The records twice: once for the exceptions, which come first, then
  // block by block into the stream; each pass in parallel blocks.
  const std::size_t n = pixels_.size();
  std::vector<std::vector<StateException>> found((n + kAddGrain - 1) / kAddGrain);
  for_each_block(n, [&](std::size_t block, std::size_t first, std::size_t count) {
    std::vector<char> record(record_bytes_);
    for (std::size_t i = first; i < first + count; ++i) encode_record(i, i, record.data(), &found[block]);
  });
  std::vector<StateException> exceptions;
  for (const auto& f : found) exceptions.insert(exceptions.end(), f.begin(), f.end());
  write_exceptions(out, exceptions);
  const std::size_t per_write = std::max<std::size_t>(kAddGrain, (std::size_t{8} << 20) / record_bytes_ / kAddGrain * kAddGrain);
  std::vector<char> buffer(std::min(n, per_write) * record_bytes_);
  for (std::size_t first = 0; first < n && out; first += per_write) {
    const std::size_t count = std::min(per_write, n - first);
    for_each_block(count, [&](std::size_t, std::size_t b, std::size_t c) {
      for (std::size_t i = b; i < b + c; ++i) encode_record(first + i, first + i, &buffer[i * record_bytes_], nullptr);
    });
    out.write(buffer.data(), static_cast<std::streamsize>(count * record_bytes_));
  }
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
  std::vector<StateException> exceptions;
  if (!read_non_finite(in, nf, error) || !read_exceptions(in, pixels_.size(), exceptions, error)) return false;
  // Integer sums cannot be corrupt in value (any bits are some sum); the
  // samples are checked against the header by the checkpoint and shard readers.
  std::vector<PixelSum> pixels(pixels_.size());
  const auto stride = static_cast<std::size_t>(sum_stride_), vstride = static_cast<std::size_t>(value_stride_);
  std::vector<ExactSum> sums(aov_sums_.size());
  std::vector<double> values(aov_values_.size());
  const StateException* ex = exceptions.data();
  std::size_t bad = SIZE_MAX;
  const bool read = read_blocks<char>(in, pixels.size(), record_bytes_, [&](const char* r, std::size_t first, std::size_t count) {
    for (std::size_t i = first; i < first + count && bad == SIZE_MAX; ++i, r += record_bytes_) {
      const StateException* end = exceptions_end(exceptions, ex, i);
      if (!decode_record(r, ex, end, pixels[i], sums.data() + i * stride, values.data() + i * vstride) ||
          !valid_ranked(sums.data() + i * stride))
        bad = i;
      ex = end;
    }
    return bad == SIZE_MAX;
  });
  if (bad != SIZE_MAX) {
    error = "corrupt film state (pixel " + std::to_string(bad) + " of the crop)";
    return false;
  }
  if (!read) {
    error = "truncated film state";
    return false;
  }
  if (in.peek() != std::char_traits<char>::eof()) {
    error = "film state has trailing data";
    return false;
  }
  pixels_ = std::move(pixels);
  aov_sums_ = std::move(sums);
  aov_values_ = std::move(values);
  non_finite_ = nf;
  return true;
}

std::size_t Film::add_records(const char* records, std::size_t first, std::size_t count,
                              const std::vector<StateException>& exceptions, const StateRules& rules) {
  const auto width = static_cast<std::size_t>(rules.crop.width());
  std::vector<ExactSum> sums(static_cast<std::size_t>(sum_stride_));
  std::vector<double> values(static_cast<std::size_t>(value_stride_));
  const StateException* ex = exceptions_from(exceptions, first);
  for (std::size_t i = first; i < first + count; ++i, records += record_bytes_) {
    prefetch_record(records, record_bytes_);
    const StateException* end = exceptions_end(exceptions, ex, i);
    PixelSum sum;
    if (!decode_record(records, ex, end, sum, sums.data(), values.data()) ||
        sum.samples > rules.max_samples[i - rules.first] || !valid_ranked(sums.data()))
      return i;
    ex = end;
    const std::size_t to = index(rules.crop.x0 + static_cast<int>(i % width), rules.crop.y0 + static_cast<int>(i / width));
    pixels_[to].add(sum);
    add_sums(to, sums.data());
    add_values(to, values.data(), rules.other_first[i - rules.first] != 0);
  }
  return SIZE_MAX;
}

std::size_t Film::set_records(const char* records, std::size_t first, std::size_t count,
                              const std::vector<StateException>& exceptions, const StateRules& rules,
                              std::size_t to0) {
  const auto stride = static_cast<std::size_t>(sum_stride_), vstride = static_cast<std::size_t>(value_stride_);
  const StateException* ex = exceptions_from(exceptions, first);
  for (std::size_t i = first; i < first + count; ++i, records += record_bytes_) {
    prefetch_record(records, record_bytes_);
    const StateException* end = exceptions_end(exceptions, ex, i);
    const std::size_t to = to0 + (i - first);
    ExactSum* sums = aov_sums_.data() + to * stride;
    double* values = aov_values_.data() + to * vstride;
    // Integer sums: 0 + x is x, and valid Cryptomatte slots (ids increasing,
    // free slots last and empty) are what add_ranked makes of them from
    // empty slots. The plain values are not: first_values.
    if (!decode_record(records, ex, end, pixels_[to], sums, values) ||
        pixels_[to].samples > rules.max_samples[i - rules.first] || !valid_ranked(sums))
      return i;
    ex = end;
    first_values(values);
  }
  return SIZE_MAX;
}

std::string Film::too_many_samples(std::size_t pixel, uint64_t samples, const StateRules& rules) {
  const auto width = static_cast<std::size_t>(rules.crop.width());
  return "its film state holds " + std::to_string(samples) + " samples in pixel (" +
         std::to_string(rules.crop.x0 + static_cast<int>(pixel % width)) + ", " +
         std::to_string(rules.crop.y0 + static_cast<int>(pixel / width)) + "), more than its pieces' " +
         std::to_string(rules.max_samples[pixel - rules.first]) + " (the two do not belong together)";
}

std::string Film::refusal(const StateView& view, std::size_t pixel, const StateRules& rules) const {
  return refusal(view.records + pixel * record_bytes_, view, pixel, rules);
}

std::string Film::refusal(const char* record, const StateView& view, std::size_t pixel, const StateRules& rules) const {
  const StateException* ex = exceptions_from(view.exceptions, pixel);
  const StateException* end = exceptions_end(view.exceptions, ex, pixel);
  PixelSum sum;
  std::vector<ExactSum> sums(static_cast<std::size_t>(sum_stride_));
  std::vector<double> values(static_cast<std::size_t>(value_stride_));
  const auto width = static_cast<std::size_t>(view.crop.width());
  const std::string where = "pixel (" + std::to_string(view.crop.x0 + static_cast<int>(pixel % width)) + ", " +
                            std::to_string(view.crop.y0 + static_cast<int>(pixel / width)) + ")";
  if (!decode_record(record, ex, end, sum, sums.data(), values.data()))
    return "corrupt film state (" + where + ": a value not stored as this pathtracer stores it)";
  if (sum.samples > rules.max_samples[pixel - rules.first]) return too_many_samples(pixel, sum.samples, rules);
  return "corrupt film state (Cryptomatte slots of " + where + ")";
}

bool Film::add_state(std::istream& in, const StateRules& rules, std::string& error) {
  PixelRect c;
  if (!read_layout(in, width_, height_, c, aovs_, error)) return false;
  if (c != rules.crop || !crop_.contains(c)) {
    error = "film state covers pixels " + c.text() + ", not " + rules.crop.text() + " inside " + crop_.text();
    return false;
  }
  StateView view;
  view.crop = c;
  const std::size_t n = static_cast<std::size_t>(c.width()) * static_cast<std::size_t>(c.height());
  if (!read_non_finite(in, view.non_finite, error) || !read_exceptions(in, n, view.exceptions, error)) return false;
  if (rules.first != 0 || rules.other_first.size() != n || rules.max_samples.size() != n) {
    error = "film state rules of the wrong size";
    return false;
  }
  std::size_t bad = SIZE_MAX;
  std::string refused;
  const bool read = read_blocks<char>(in, n, record_bytes_, [&](const char* r, std::size_t first, std::size_t count) {
    bad = add_records(r, first, count, view.exceptions, rules);
    if (bad != SIZE_MAX) refused = refusal(r + (bad - first) * record_bytes_, view, bad, rules);
    return bad == SIZE_MAX;
  });
  if (bad != SIZE_MAX || !read) {
    error = bad != SIZE_MAX ? refused : "truncated film state";
    return false;
  }
  if (in.peek() != std::char_traits<char>::eof()) {
    error = "film state has trailing data";
    return false;
  }
  non_finite_.merge(view.non_finite);
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
  const std::size_t n = static_cast<std::size_t>(c.width()) * static_cast<std::size_t>(c.height());
  if (!read_non_finite(in, view.non_finite, error) || !read_exceptions(in, n, view.exceptions, error)) return false;
  // The whole body is checked for its size before any of it is added.
  const std::size_t header = buffer.consumed(), body = n * record_bytes_;
  if (state.size() - header != body) {
    error = state.size() - header < body ? "truncated film state" : "film state has trailing data";
    return false;
  }
  view.crop = c;
  view.records = state.data() + header;
  return true;
}

std::size_t Film::add_state_rows(const StateView& view, const StateRules& rules, int y0, int y1) {
  return add_state_rect(view, rules, {view.crop.x0, y0, view.crop.x1, y1});
}

std::size_t Film::set_state_rows(const StateView& view, const StateRules& rules, int y0, int y1) {
  return set_state_rect(view, rules, {view.crop.x0, y0, view.crop.x1, y1});
}

std::size_t Film::add_state_rect(const StateView& view, const StateRules& rules, const PixelRect& rect) {
  const auto width = static_cast<std::size_t>(view.crop.width()), count = static_cast<std::size_t>(rect.width());
  for (int y = rect.y0; y < rect.y1; ++y) {
    const std::size_t first = static_cast<std::size_t>(y - view.crop.y0) * width + static_cast<std::size_t>(rect.x0 - view.crop.x0);
    const std::size_t bad = add_records(view.records + first * record_bytes_, first, count, view.exceptions, rules);
    if (bad != SIZE_MAX) return bad;
  }
  return SIZE_MAX;
}

std::size_t Film::set_state_rect(const StateView& view, const StateRules& rules, const PixelRect& rect) {
  move_to(rect);
  const auto width = static_cast<std::size_t>(view.crop.width()), count = static_cast<std::size_t>(rect.width());
  for (int y = rect.y0; y < rect.y1; ++y) {
    const std::size_t first = static_cast<std::size_t>(y - view.crop.y0) * width + static_cast<std::size_t>(rect.x0 - view.crop.x0);
    const std::size_t to = static_cast<std::size_t>(y - rect.y0) * count;
    const std::size_t bad = set_records(view.records + first * record_bytes_, first, count, view.exceptions, rules, to);
    if (bad != SIZE_MAX) {  // the pixels from the refused one on: as in a cleared film
      const auto from = static_cast<std::ptrdiff_t>(to + (bad - first));
      std::fill(pixels_.begin() + from, pixels_.end(), PixelSum{});
      std::fill(aov_sums_.begin() + from * sum_stride_, aov_sums_.end(), ExactSum{});
      std::fill(aov_values_.begin() + from * value_stride_, aov_values_.end(), 0.0);
      return bad;
    }
  }
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
  const std::size_t bad = for_blocks(n, [&](std::size_t first, std::size_t count) {
    return std::min(n, add_records(view.records + first * record_bytes_, first, count, view.exceptions, rules));
  });
  if (bad < n) {
    error = refusal(view, bad, rules);
    return false;
  }
  non_finite_.merge(view.non_finite);
  return true;
}

}  // namespace pt
