// Film::write_state / read_state: checkpoints of a film, bit for bit.
#include <algorithm>
#include <array>
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

// State layout (version 6), all little-endian:
//   the 8-byte magic; uint32 version, width, height; int32 crop x0, y0, x1, y1;
//   uint32 AOV count, then per AOV uint8 type, uint8 channel type and uint8
//   ranks (Cryptomatte; 0 for the others);
//   the non-finite report: uint64 nan, pos_inf, neg_inf; uint8 has_first;
//   int32 x, y, sample; float r, g, b;
//   the defaults: a full record (below) of the slots every pixel of the crop
//   holds alike (pixel 0's value there), 0 in the other slots;
//   uint64 the number of exceptions, then each: uint64 pixel (of the crop,
//   row-major), uint32 slot, its value as 128 bits (the low 64 first), in
//   increasing (pixel, slot) order;
//   the record index: per group of 32 pixels of the crop (row-major; the
//   last may be shorter), uint64 where its records begin, from the first
//   record; then uint64 the records' size;
//   per pixel of the crop (row-major, top row first), its record
//   (film_state_codec.cpp): a mask of ceil(slots / 8) bytes (bit k of byte
//   k / 8 for slot k), then the slots it sets, in slot order, at their
//   widths; a slot not set holds its default.
// A full record holds every slot: r, g, b, weight and coverage as int64
// (exact sums, render/film/exact_sum.h: integers in units of 2^-44), samples
// as uint32, the AOVs' exact sums in request order as int64 (a Cryptomatte
// layer: per rank, its id's 32 bits as uint32 and its weight as int64), then
// the AOVs' plain values as floats. A slot whose value its type cannot hold
// is 0 there and listed among the exceptions with its full value (a sum's
// 128-bit integer, the count, a value's double bits). A record sets exactly
// the slots whose value differs from its default: a slot with a default
// other than 0 is set by no record, and a set slot is not 0.
// Versions 1 (beauty only, no crop), 2 (sums in double), 3 (either sums in
// double with coverage, or exact sums without it), 4 (every sum in 128
// bits, values in double: 992 bytes a pixel with every AOV) and 5 (every
// record full: 448 bytes a pixel with every AOV) are no longer read.
constexpr char kMagic[8] = {'P', 'T', 'F', 'I', 'L', 'M', '\r', '\n'};
constexpr uint32_t kStateVersion = 6;
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

// Reads the records of a state's groups [0, groups) from a stream in
// batches of about 8 MiB, pointing `view` at each batch and calling
// `add(first_pixel, pixel_count)`: false if the stream ends first or `add`
// refuses.
template <typename F>
bool read_groups(std::istream& in, StateView& view, std::size_t pixels, F&& add) {
  const std::vector<uint64_t>& index = view.codec.index;
  const std::size_t groups = index.size() - 1;
  std::vector<char> batch;
  for (std::size_t g0 = 0, g1 = 0; g0 < groups; g0 = g1) {
    g1 = g0 + 1;
    while (g1 < groups && index[g1 + 1] - index[g0] <= (std::size_t{8} << 20)) ++g1;
    batch.resize(index[g1] - index[g0]);
    if (!in.read(batch.data(), static_cast<std::streamsize>(batch.size()))) return false;
    view.records = batch.data();
    view.records_from = index[g0];
    const std::size_t first = g0 * kStateGroup;
    if (!add(first, std::min(pixels, g1 * kStateGroup) - first)) return false;
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

// Asks for the bytes a few records after `at` to be brought into the
// cache: a state's records stream from a mapped file, whose pages the
// hardware prefetcher does not cross.
constexpr std::size_t kPrefetchBytes = 1024;
inline void prefetch_records(const char* at) {
  __builtin_prefetch(at + kPrefetchBytes);
  __builtin_prefetch(at + kPrefetchBytes + 64);
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
  std::vector<StateException> exceptions;
  const StateCodec codec = state_codec(exceptions);
  write_codec(out, codec, exceptions);
  // The records, in batches of groups of about 8 MiB, each encoded in parallel.
  const std::size_t n = pixels_.size(), groups = codec.index.size() - 1;
  std::vector<char> batch;
  for (std::size_t g0 = 0, g1 = 0; g0 < groups && out; g0 = g1) {
    g1 = g0 + 1;
    while (g1 < groups && codec.index[g1 + 1] - codec.index[g0] <= (std::size_t{8} << 20)) ++g1;
    batch.resize(codec.index[g1] - codec.index[g0]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(g0, g1, kAddGrain / kStateGroup), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<char> full(record_bytes_);
      char* to = batch.data() + (codec.index[r.begin()] - codec.index[g0]);
      for (std::size_t i = r.begin() * kStateGroup; i < std::min(n, r.end() * kStateGroup); ++i) {
        encode_record(i, i, full.data(), nullptr);
        to += pack_record(full.data(), codec, to);
      }
    });
    out.write(batch.data(), static_cast<std::streamsize>(batch.size()));
  }
  return static_cast<bool>(out);
}

bool Film::read_state(std::istream& in, std::string& error) {
  StateView view;
  if (!read_layout(in, width_, height_, view.crop, aovs_, error)) return false;
  if (view.crop != crop_) {
    error = "film state covers pixels " + view.crop.text() + ", the render's crop is " + crop_.text();
    return false;
  }
  const std::size_t n = pixels_.size();
  if (!read_non_finite(in, view.non_finite, error) || !read_codec(in, n, view.codec, view.exceptions, error))
    return false;
  // Integer sums cannot be corrupt in value (any bits are some sum); the
  // samples are checked against the header by the checkpoint and shard readers.
  std::vector<PixelSum> pixels(n);
  const auto stride = static_cast<std::size_t>(sum_stride_), vstride = static_cast<std::size_t>(value_stride_);
  std::vector<ExactSum> sums(aov_sums_.size());
  std::vector<double> values(aov_values_.size());
  std::size_t bad = SIZE_MAX;
  const bool read = read_groups(in, view, n, [&](std::size_t first, std::size_t count) {
    bad = for_each_record(
        view, first, count,
        [&](std::size_t i) { return DecodedPixel{&pixels[i], sums.data() + i * stride, values.data() + i * vstride}; },
        [](std::size_t, const DecodedPixel&) { return true; });
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
  // The defaults must be the ones write_state finds in these pixels (the
  // slots every pixel holds alike): what is read is written back byte for byte.
  std::swap(pixels_, pixels);
  std::swap(aov_sums_, sums);
  std::swap(aov_values_, values);
  std::vector<StateException> exceptions;
  if (state_codec(exceptions).defaults != view.codec.defaults) {
    std::swap(pixels_, pixels);
    std::swap(aov_sums_, sums);
    std::swap(aov_values_, values);
    error = "corrupt film state (defaults not those of its pixels)";
    return false;
  }
  non_finite_ = view.non_finite;
  return true;
}

bool Film::seek_record(const StateView& view, std::size_t pixel, const char*& at, const char*& end) const {
  const std::size_t group = pixel / kStateGroup;
  at = view.records + (view.codec.index[group] - view.records_from);
  end = view.records + (view.codec.index[group + 1] - view.records_from);
  for (std::size_t i = group * kStateGroup; i < pixel; ++i) {
    const std::size_t size = record_size(at, end, view.codec);
    if (size == 0) return false;
    at += size;
  }
  return true;
}

bool Film::next_record(const StateView& view, std::size_t pixel, std::size_t pixels, const char* at,
                       const char*& end) {
  if ((pixel + 1) % kStateGroup != 0 && pixel + 1 != pixels) return true;
  if (at != end) return false;
  if (pixel + 1 < pixels) end = view.records + (view.codec.index[(pixel + 1) / kStateGroup + 1] - view.records_from);
  return true;
}

namespace {
std::size_t pixels_of(const PixelRect& crop) {
  return static_cast<std::size_t>(crop.width()) * static_cast<std::size_t>(crop.height());
}
}  // namespace

template <typename Target, typename Use>
std::size_t Film::for_each_record(const StateView& view, std::size_t first, std::size_t count, Target&& target,
                                  Use&& use) const {
  const std::size_t n = pixels_of(view.crop);
  const StateException* ex = exceptions_from(view.exceptions, first);
  const char *at = nullptr, *end = nullptr;
  if (!seek_record(view, first, at, end)) return first;
  for (std::size_t i = first; i < first + count; ++i) {
    prefetch_records(at);
    const StateException* ex_end = exceptions_end(view.exceptions, ex, i);
    DecodedPixel d = target(i);
    if (!decode_record(at, end, view.codec, ex, ex_end, d) || !valid_ranked(d.sums, d.held, view.codec.varying) ||
        !next_record(view, i, n, at, end) || !use(i, d))
      return i;
    ex = ex_end;
  }
  return SIZE_MAX;
}

std::size_t Film::add_records(const StateView& view, std::size_t first, std::size_t count, const StateRules& rules) {
  const auto width = static_cast<std::size_t>(rules.crop.width());
  // A scratch that holds the state's defaults but for the slots the last
  // record held (all of them 0 by default), which are cleared after it is
  // added: the plain sums added are those it held and the defaults that are
  // not 0, not every slot.
  PixelSum sum;
  std::vector<ExactSum> sums(view.codec.sums);
  std::vector<double> values(view.codec.values);
  const DecodedPixel scratch{&sum, sums.data(), values.data(), true};
  std::array<uint64_t, kStateWords> shared{};  // the slots whose default is not 0
  for (std::size_t w = 0; w < kStateWords; ++w) shared[w] = ~view.codec.varying[w];
  std::size_t x = first % width, y = first / width;  // pixel i's, in the crop (no division per pixel)
  return for_each_record(view, first, count, [&](std::size_t) { return scratch; },
                         [&](std::size_t i, const DecodedPixel& d) {
                           if (d.sum->samples > rules.max_samples[i - rules.first]) return false;
                           const std::size_t to = index(rules.crop.x0 + static_cast<int>(x), rules.crop.y0 + static_cast<int>(y));
                           if (++x == width) x = 0, ++y;
                           pixels_[to].add(*d.sum);
                           std::array<uint64_t, kStateWords> slots{};
                           for (std::size_t w = 0; w < kStateWords; ++w) slots[w] = d.held[w] | shared[w];
                           add_sums(to, d.sums, slots);
                           add_values(to, d.values, rules.other_first[i - rules.first] != 0);
                           for_each_slot(d.held, aov_sum_slots_, [&](std::size_t k) { d.sums[k - kAovSlot] = ExactSum{}; });
                           const std::size_t v0 = kAovSlot + static_cast<std::size_t>(sum_stride_);
                           for_each_slot(d.held, value_slots_, [&](std::size_t k) { d.values[k - v0] = 0.0; });
                           return true;
                         });
}

std::size_t Film::set_records(const StateView& view, std::size_t first, std::size_t count, const StateRules& rules,
                              std::size_t to0) {
  const auto stride = static_cast<std::size_t>(sum_stride_), vstride = static_cast<std::size_t>(value_stride_);
  // Integer sums: 0 + x is x, and valid Cryptomatte slots (ids increasing,
  // free slots last and empty) are what add_ranked makes of them from
  // empty slots. The plain values are not: first_values.
  const auto target = [&](std::size_t i) {
    const std::size_t to = to0 + (i - first);
    return DecodedPixel{&pixels_[to], aov_sums_.data() + to * stride, aov_values_.data() + to * vstride};
  };
  return for_each_record(view, first, count, target, [&](std::size_t i, const DecodedPixel& d) {
    if (d.sum->samples > rules.max_samples[i - rules.first]) return false;
    first_values(d.values);
    return true;
  });
}

std::string Film::too_many_samples(std::size_t pixel, uint64_t samples, const StateRules& rules) {
  const auto width = static_cast<std::size_t>(rules.crop.width());
  return "its film state holds " + std::to_string(samples) + " samples in pixel (" +
         std::to_string(rules.crop.x0 + static_cast<int>(pixel % width)) + ", " +
         std::to_string(rules.crop.y0 + static_cast<int>(pixel / width)) + "), more than its pieces' " +
         std::to_string(rules.max_samples[pixel - rules.first]) + " (the two do not belong together)";
}

std::string Film::refusal(const StateView& view, std::size_t pixel, const StateRules& rules) const {
  const StateException* ex = exceptions_from(view.exceptions, pixel);
  const StateException* ex_end = exceptions_end(view.exceptions, ex, pixel);
  PixelSum sum;
  std::vector<ExactSum> sums(static_cast<std::size_t>(sum_stride_));
  std::vector<double> values(static_cast<std::size_t>(value_stride_));
  DecodedPixel d{&sum, sums.data(), values.data()};
  const auto width = static_cast<std::size_t>(view.crop.width());
  const std::string where = "pixel (" + std::to_string(view.crop.x0 + static_cast<int>(pixel % width)) + ", " +
                            std::to_string(view.crop.y0 + static_cast<int>(pixel / width)) + ")";
  const char *at = nullptr, *end = nullptr;
  if (!seek_record(view, pixel, at, end) || !decode_record(at, end, view.codec, ex, ex_end, d))
    return "corrupt film state (" + where + ": a value not stored as this pathtracer stores it)";
  if (sum.samples > rules.max_samples[pixel - rules.first]) return too_many_samples(pixel, sum.samples, rules);
  if (!valid_ranked(sums.data())) return "corrupt film state (Cryptomatte slots of " + where + ")";
  return "corrupt film state (" + where + ": its records do not end where the record index says)";
}

bool Film::add_state(std::istream& in, const StateRules& rules, std::string& error) {
  StateView view;
  if (!read_layout(in, width_, height_, view.crop, aovs_, error)) return false;
  if (view.crop != rules.crop || !crop_.contains(view.crop)) {
    error = "film state covers pixels " + view.crop.text() + ", not " + rules.crop.text() + " inside " + crop_.text();
    return false;
  }
  const std::size_t n = pixels_of(view.crop);
  if (!read_non_finite(in, view.non_finite, error) || !read_codec(in, n, view.codec, view.exceptions, error))
    return false;
  if (rules.first != 0 || rules.other_first.size() != n || rules.max_samples.size() != n) {
    error = "film state rules of the wrong size";
    return false;
  }
  std::size_t bad = SIZE_MAX;
  std::string refused;
  const bool read = read_groups(in, view, n, [&](std::size_t first, std::size_t count) {
    bad = add_records(view, first, count, rules);
    if (bad != SIZE_MAX) refused = refusal(view, bad, rules);
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
  const std::size_t n = pixels_of(c);
  if (!read_non_finite(in, view.non_finite, error) || !read_codec(in, n, view.codec, view.exceptions, error))
    return false;
  // The whole body is checked for its size before any of it is added.
  const std::size_t header = buffer.consumed(), body = view.codec.index.back();
  if (state.size() - header != body) {
    error = state.size() - header < body ? "truncated film state" : "film state has trailing data";
    return false;
  }
  view.crop = c;
  view.records = state.data() + header;
  view.records_from = 0;
  return true;
}

std::size_t Film::state_record_at(std::string_view state, std::size_t pixel) const {
  StateView view;
  std::string error;
  MemoryBuffer buffer(state);
  std::istream in(&buffer);
  if (!read_layout(in, width_, height_, view.crop, aovs_, error) || !read_non_finite(in, view.non_finite, error) ||
      !read_codec(in, pixels_of(view.crop), view.codec, view.exceptions, error) || pixel >= pixels_of(view.crop))
    return std::string::npos;
  const std::size_t header = buffer.consumed();
  if (state.size() - header != view.codec.index.back()) return std::string::npos;
  view.records = state.data() + header;
  const char *at = nullptr, *end = nullptr;
  if (!seek_record(view, pixel, at, end)) return std::string::npos;
  return static_cast<std::size_t>(at - state.data());
}

std::size_t Film::state_slot_at(std::string_view state, std::size_t pixel, uint32_t slot) const {
  const std::size_t record = state_record_at(state, pixel);
  if (record == std::string::npos || slot >= state_slots() || state.size() - record < bitmap_bytes_)
    return std::string::npos;
  std::array<uint64_t, kStateWords> mask{};
  std::memcpy(mask.data(), state.data() + record, bitmap_bytes_);
  if (((mask[slot / 64] >> (slot % 64)) & 1) == 0) return std::string::npos;
  std::size_t offset = bitmap_bytes_;
  for (uint32_t k = 0; k < slot; ++k)
    if (((mask[k / 64] >> (k % 64)) & 1) != 0)
      offset += (k + 1 < state_slots() ? slot_offset_[k + 1] : record_bytes_) - slot_offset_[k];
  return record + offset;
}

std::size_t Film::add_state_rect(const StateView& view, const StateRules& rules, const PixelRect& rect) {
  const auto width = static_cast<std::size_t>(view.crop.width()), count = static_cast<std::size_t>(rect.width());
  for (int y = rect.y0; y < rect.y1; ++y) {
    const std::size_t first = static_cast<std::size_t>(y - view.crop.y0) * width + static_cast<std::size_t>(rect.x0 - view.crop.x0);
    const std::size_t bad = add_records(view, first, count, rules);
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
    const std::size_t bad = set_records(view, first, count, rules, to);
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
  if (rules.first != 0 || rules.other_first.size() != n || n != pixels_of(view.crop)) {
    error = "film state rules of the wrong size";
    return false;
  }
  const std::size_t bad = for_blocks(n, [&](std::size_t first, std::size_t count) {
    return std::min(n, add_records(view, first, count, rules));
  });
  if (bad < n) {
    error = refusal(view, bad, rules);
    return false;
  }
  non_finite_.merge(view.non_finite);
  return true;
}

}  // namespace pt
