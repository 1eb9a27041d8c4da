// The film state's pixel records (version 6; the layout is in
// film_state.cpp): every slot of a pixel in the narrowest type that holds the
// values a render makes, and the rare slot that does not fit in an exception
// list with its full value; a record holds only the slots that differ from
// the state's defaults (0, or the value every pixel of the state shares),
// after a mask of them. Exact either way: a state decodes to the very
// integers and doubles the film held, so merges and resumed renders keep
// their bits, and there is one encoding of a film (what is read back is
// written back byte for byte).
//
// The types: an exact sum as int64 (a shard's sum fits unless the pixel's
// value reaches 2^19 over its samples), a Cryptomatte id (32 bits) and the
// sample count as uint32, a plain value (first-sample P, Z, ids and their
// flags; the non-finite maximum: floats or 0/1) as a float. A float slot
// holds zeros, normal numbers, infinities and quiet NaNs only, so that no
// denormals-are-zero mode of the reader or the writer can change it.
#include <algorithm>
#include <bit>
#include <bitset>
#include <cstring>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "render/film/film.h"

namespace pt {
namespace {

enum SlotKind : uint8_t { kWide64, kNarrow32, kFloat32 };  // int64 sum; uint32 id or count; float value
// A state slot's kind and where it decodes to: the beauty's sums (int64), its
// count (uint32), an AOV sum (int64, or uint32 for a Cryptomatte id), an AOV
// value (float).
enum SlotRole : uint8_t { kBeautySlot, kCountSlot, kWideSumSlot, kNarrowSumSlot, kValueSlot };

constexpr std::size_t kBeautySums = 5;  // r, g, b, weight, coverage
// Pixels per block of the parallel passes over a film (defaults, exceptions).
constexpr std::size_t kStateBlock = 4096;
constexpr std::size_t kExceptionBytes = sizeof(uint64_t) + sizeof(uint32_t) + 2 * sizeof(uint64_t);

bool fits_int64(UInt128 v) {
  const auto low = static_cast<int64_t>(static_cast<uint64_t>(v));
  return static_cast<uint64_t>(v >> 64) == static_cast<uint64_t>(low >> 63);
}
bool fits_uint32(UInt128 v) { return v >> 32 == 0; }

// A float that converts to double and back unchanged under any FP mode.
bool plain_float(uint32_t bits) {
  const uint32_t exponent = (bits >> 23) & 0xffu, mantissa = bits & 0x7fffffu;
  if (exponent == 0) return mantissa == 0;         // zeros, not denormals
  if (exponent == 0xffu) return mantissa == 0 || (mantissa & 0x400000u) != 0;  // infinities, quiet NaNs
  return true;
}
// The float bits of `value` when a float holds it exactly (and plain_float).
bool as_float(double value, uint32_t& bits) {
  const float f = static_cast<float>(value);
  bits = std::bit_cast<uint32_t>(f);
  return plain_float(bits) && std::bit_cast<uint64_t>(static_cast<double>(f)) == std::bit_cast<uint64_t>(value);
}

template <typename T>
T load(const char*& p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  p += sizeof v;
  return v;
}
template <typename T>
void store(char*& p, T v) {
  std::memcpy(p, &v, sizeof v);
  p += sizeof v;
}

ExactSum from_int64(int64_t v) {
  ExactSum s;
  s.set_raw(static_cast<UInt128>(static_cast<Int128>(v)));
  return s;
}

// An exact sum's slot: int64, or 0 with an exception.
void store_sum(char*& p, const ExactSum& s, uint64_t pixel, uint32_t slot, std::vector<StateException>* ex) {
  const bool fits = fits_int64(s.raw());
  store(p, fits ? static_cast<int64_t>(static_cast<uint64_t>(s.raw())) : int64_t{0});
  if (!fits && ex) ex->push_back({pixel, slot, s.raw()});
}
void store_narrow(char*& p, UInt128 v, uint64_t pixel, uint32_t slot, std::vector<StateException>* ex) {
  const bool fits = fits_uint32(v);
  store(p, fits ? static_cast<uint32_t>(v) : uint32_t{0});
  if (!fits && ex) ex->push_back({pixel, slot, v});
}

}  // namespace

void Film::init_state_layout() {
  static_assert(kAovSlot == kBeautySums + 1, "a state's AOV sums follow the beauty's sums and its count");
  sum_kinds_.assign(static_cast<std::size_t>(sum_stride_), kWide64);
  for (const SumRun& run : sum_runs_)
    for (int k = 0; k < run.ranks; ++k) sum_kinds_[static_cast<std::size_t>(run.offset + 2 * k)] = kNarrow32;
  // Every slot's kind, in slot order: the beauty's sums and count, the AOV
  // sums, the values.
  std::vector<uint8_t> kinds(kBeautySums, kWide64);
  kinds.push_back(kNarrow32);
  kinds.insert(kinds.end(), sum_kinds_.begin(), sum_kinds_.end());
  kinds.insert(kinds.end(), static_cast<std::size_t>(value_stride_), kFloat32);
  // At most 111 slots (every AOV of the catalogue, Cryptomatte at its most
  // ranks): a catalogue that outgrows kStateWords is a programming error.
  if (kinds.size() > 64 * kStateWords) throw std::logic_error("film state slots outgrow kStateWords");
  slot_kind_.assign(kBeautySums, kBeautySlot);
  slot_kind_.push_back(kCountSlot);
  for (uint8_t kind : sum_kinds_) slot_kind_.push_back(kind == kWide64 ? kWideSumSlot : kNarrowSumSlot);
  slot_kind_.insert(slot_kind_.end(), static_cast<std::size_t>(value_stride_), kValueSlot);
  slot_offset_.clear();
  wide_slots_.fill(0);
  aov_sum_slots_.fill(0);
  value_slots_.fill(0);
  plain_sum_slots_.fill(0);
  for (std::size_t k = kAovSlot; k < kinds.size(); ++k) {
    auto& set = slot_kind_[k] == kValueSlot ? value_slots_ : aov_sum_slots_;
    set[k / 64] |= uint64_t{1} << (k % 64);
  }
  for (const SumRun& run : sum_runs_) {
    for (int j = 0; j < run.count && run.ranks == 0; ++j) {
      const std::size_t k = kAovSlot + static_cast<std::size_t>(run.offset + j);
      plain_sum_slots_[k / 64] |= uint64_t{1} << (k % 64);
    }
  }
  record_bytes_ = 0;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    slot_offset_.push_back(static_cast<uint32_t>(record_bytes_));
    record_bytes_ += kinds[k] == kWide64 ? sizeof(int64_t) : sizeof(uint32_t);
    if (kinds[k] == kWide64) wide_slots_[k / 64] |= uint64_t{1} << (k % 64);
  }
  bitmap_bytes_ = (kinds.size() + 7) / 8;
}

void Film::encode_record(std::size_t pixel, uint64_t number, char* out, std::vector<StateException>* ex) const {
  const PixelSum& p = pixels_[pixel];
  const ExactSum* beauty[kBeautySums] = {&p.r, &p.g, &p.b, &p.weight, &p.coverage};
  for (uint32_t k = 0; k < kBeautySums; ++k) store_sum(out, *beauty[k], number, k, ex);
  store_narrow(out, p.samples, number, kBeautySums, ex);
  const auto sums = static_cast<std::size_t>(sum_stride_), values = static_cast<std::size_t>(value_stride_);
  const ExactSum* s = aov_sums_.data() + pixel * sums;
  for (std::size_t k = 0; k < sums; ++k) {
    const auto slot = static_cast<uint32_t>(kBeautySums + 1 + k);
    if (sum_kinds_[k] == kWide64) {
      store_sum(out, s[k], number, slot, ex);
    } else {
      store_narrow(out, s[k].raw(), number, slot, ex);
    }
  }
  const double* v = aov_values_.data() + pixel * values;
  for (std::size_t k = 0; k < values; ++k) {
    uint32_t bits = 0;
    const bool fits = as_float(v[k], bits);
    store(out, fits ? bits : uint32_t{0});
    if (!fits && ex) ex->push_back({number, static_cast<uint32_t>(kBeautySums + 1 + sums + k), std::bit_cast<uint64_t>(v[k])});
  }
}

std::size_t Film::pack_record(const char* full, const StateCodec& codec, char* out) const {
  const std::size_t slots = slot_offset_.size();
  std::array<uint64_t, kStateWords> mask{};
  std::size_t size = bitmap_bytes_;
  char* to = out ? out + bitmap_bytes_ : nullptr;
  for (std::size_t k = 0; k < slots; ++k) {
    const std::size_t at = slot_offset_[k], width = (k + 1 < slots ? slot_offset_[k + 1] : record_bytes_) - at;
    if (std::memcmp(full + at, codec.defaults.data() + at, width) == 0) continue;
    mask[k / 64] |= uint64_t{1} << (k % 64);
    if (to) std::memcpy(to, full + at, width), to += width;
    size += width;
  }
  if (out) {
    for (std::size_t b = 0; b < bitmap_bytes_; ++b) out[b] = static_cast<char>(mask[b / 8] >> (8 * (b % 8)));
  }
  return size;
}

StateCodec Film::state_codec(std::vector<StateException>& exceptions) const {
  StateCodec codec;
  codec.defaults.assign(record_bytes_, 0);
  const std::size_t n = pixels_.size(), slots = slot_offset_.size();
  if (n == 0) {
    codec.index.assign(1, 0);
    for (std::size_t k = 0; k < slots; ++k) codec.varying[k / 64] |= uint64_t{1} << (k % 64);
    return codec;
  }
  // The defaults: the slots every pixel's full record shares with pixel 0's
  // (0 elsewhere). Blocks of pixels in parallel, each with its exceptions
  // and the slots where it differs.
  std::vector<char> first(record_bytes_);
  encode_record(0, 0, first.data(), nullptr);
  const std::size_t blocks = (n + kStateBlock - 1) / kStateBlock;
  std::vector<std::vector<StateException>> found(blocks);
  std::vector<std::vector<char>> differs(blocks, std::vector<char>(slots, 0));
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::vector<char> full(record_bytes_);
    for (std::size_t i = b * kStateBlock; i < std::min(n, (b + 1) * kStateBlock); ++i) {
      encode_record(i, i, full.data(), &found[b]);
      for (std::size_t k = 0; k < slots; ++k) {
        const std::size_t at = slot_offset_[k], width = (k + 1 < slots ? slot_offset_[k + 1] : record_bytes_) - at;
        differs[b][k] |= static_cast<char>(std::memcmp(full.data() + at, first.data() + at, width) != 0);
      }
    }
  });
  exceptions.clear();
  for (const auto& f : found) exceptions.insert(exceptions.end(), f.begin(), f.end());
  for (std::size_t k = 0; k < slots; ++k) {
    const std::size_t at = slot_offset_[k], width = (k + 1 < slots ? slot_offset_[k + 1] : record_bytes_) - at;
    const bool shared = std::none_of(differs.begin(), differs.end(), [&](const std::vector<char>& d) { return d[k] != 0; });
    if (shared) std::memcpy(codec.defaults.data() + at, first.data() + at, width);
    if (std::all_of(codec.defaults.data() + at, codec.defaults.data() + at + width, [](char c) { return c == 0; }))
      codec.varying[k / 64] |= uint64_t{1} << (k % 64);
  }
  // The record index: every group's size, then their offsets.
  const std::size_t groups = (n + kStateGroup - 1) / kStateGroup;
  codec.index.assign(groups + 1, 0);
  tbb::parallel_for(std::size_t{0}, groups, [&](std::size_t g) {
    std::vector<char> full(record_bytes_);
    uint64_t size = 0;
    for (std::size_t i = g * kStateGroup; i < std::min(n, (g + 1) * kStateGroup); ++i) {
      encode_record(i, i, full.data(), nullptr);
      size += pack_record(full.data(), codec, nullptr);
    }
    codec.index[g + 1] = size;
  });
  for (std::size_t g = 0; g < groups; ++g) codec.index[g + 1] += codec.index[g];
  return codec;
}

std::size_t Film::record_size(const char* in, const char* end, const StateCodec& codec) const {
  const auto room = static_cast<std::size_t>(end - in);
  if (room < bitmap_bytes_) return 0;
  std::array<uint64_t, kStateWords> mask{};
  std::memcpy(mask.data(), in, bitmap_bytes_);
  std::size_t size = bitmap_bytes_;
  for (std::size_t w = 0; w < kStateWords; ++w) {
    if ((mask[w] & ~codec.varying[w]) != 0) return 0;  // a slot past the last, or one every pixel shares
    size += 4 * static_cast<std::size_t>(std::popcount(mask[w]) + std::popcount(mask[w] & wide_slots_[w]));
  }
  return size <= room ? size : 0;
}

bool Film::decode_record(const char*& in, const char* end, const StateCodec& codec, const StateException* ex,
                         const StateException* ex_end, DecodedPixel& to) const {
  PixelSum& p = *to.sum;
  ExactSum* sums = to.sums;
  double* values = to.values;
  // Near its group's end the record's size is checked before it is read;
  // elsewhere no record can reach the end.
  const auto room = static_cast<std::size_t>(end - in);
  std::array<uint64_t, kStateWords> mask{};
  if (room < bitmap_bytes_ + record_bytes_ || room < sizeof mask) {
    if (record_size(in, end, codec) == 0) return false;
    std::memcpy(mask.data(), in, bitmap_bytes_);
  } else {
    std::memcpy(mask.data(), in, sizeof mask);  // the mask and what follows it
    for (std::size_t w = 0; w < kStateWords; ++w) {
      const std::size_t bits = std::min<std::size_t>(64, 8 * bitmap_bytes_ - std::min(8 * bitmap_bytes_, 64 * w));
      mask[w] &= bits == 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1;
      if ((mask[w] & ~codec.varying[w]) != 0) return false;  // a slot past the last, or one every pixel shares
    }
  }
  // The defaults, then the slots the record holds, in slot order: the
  // beauty's sums and count, the AOV sums, the values (a loop for each, so
  // that the slot's kind is not looked up per slot).
  p = codec.pixel;
  const auto n = static_cast<std::size_t>(sum_stride_);
  if (!to.defaults) {
    std::copy(codec.sums.begin(), codec.sums.end(), sums);
    std::copy(codec.values.begin(), codec.values.end(), values);
  }
  ExactSum* beauty[kBeautySums] = {&p.r, &p.g, &p.b, &p.weight, &p.coverage};
  const char* at = in + bitmap_bytes_;
  bool bad = false;  // a slot held as 0 (only a default is), or a float that is not plain
  for (uint64_t m = mask[0] & ((uint64_t{1} << kBeautySums) - 1); m != 0; m &= m - 1) {
    ExactSum& sum = *beauty[std::countr_zero(m)];
    sum = from_int64(load<int64_t>(at));
    bad |= sum.is_zero();
  }
  if (((mask[0] >> kBeautySums) & 1) != 0) {
    p.samples = load<uint32_t>(at);
    bad |= p.samples == 0;
  }
  for_each_slot(mask, aov_sum_slots_, [&](std::size_t k) {
    ExactSum& sum = sums[k - kBeautySums - 1];
    if (((wide_slots_[k / 64] >> (k % 64)) & 1) != 0) {
      sum = from_int64(load<int64_t>(at));
    } else {
      sum.set_raw(load<uint32_t>(at));
    }
    bad |= sum.is_zero();
  });
  for_each_slot(mask, value_slots_, [&](std::size_t k) {
    const auto bits = load<uint32_t>(at);
    bad |= bits == 0 || !plain_float(bits);
    values[k - kBeautySums - 1 - n] = static_cast<double>(std::bit_cast<float>(bits));
  });
  if (bad) return false;
  to.held = mask;
  // The exceptions' slots are not held (the defaults of those slots are 0:
  // valid_exception); their values replace the zeros.
  for (const StateException* e = ex; e != ex_end; ++e) {
    const uint32_t k = e->slot;
    if (((mask[k / 64] >> (k % 64)) & 1) != 0) return false;
    to.held[k / 64] |= uint64_t{1} << (k % 64);
    if (k < kBeautySums) {
      beauty[k]->set_raw(e->value);
    } else if (k == kBeautySums) {
      p.samples = static_cast<uint64_t>(e->value);
    } else if (k < kBeautySums + 1 + n) {
      sums[k - kBeautySums - 1].set_raw(e->value);
    } else {
      values[k - kBeautySums - 1 - n] = std::bit_cast<double>(static_cast<uint64_t>(e->value));
    }
  }
  in = at;
  return true;
}

void Film::decode_defaults(StateCodec& codec) const {
  const auto n = static_cast<std::size_t>(sum_stride_);
  codec.pixel = PixelSum{};
  codec.sums.assign(n, ExactSum{});
  codec.values.assign(static_cast<std::size_t>(value_stride_), 0.0);
  ExactSum* beauty[kBeautySums] = {&codec.pixel.r, &codec.pixel.g, &codec.pixel.b, &codec.pixel.weight,
                                   &codec.pixel.coverage};
  for (std::size_t k = 0; k < slot_kind_.size(); ++k) {
    const char* at = codec.defaults.data() + slot_offset_[k];
    switch (slot_kind_[k]) {
      case kBeautySlot: *beauty[k] = from_int64(load<int64_t>(at)); break;
      case kCountSlot: codec.pixel.samples = load<uint32_t>(at); break;
      case kWideSumSlot: codec.sums[k - kBeautySums - 1] = from_int64(load<int64_t>(at)); break;
      case kNarrowSumSlot: codec.sums[k - kBeautySums - 1].set_raw(load<uint32_t>(at)); break;
      default: codec.values[k - kBeautySums - 1 - n] = static_cast<double>(std::bit_cast<float>(load<uint32_t>(at)));
    }
  }
}

bool Film::valid_exception(const StateException& e, std::size_t pixels, const StateCodec& codec) const {
  if (e.pixel >= pixels || e.slot >= state_slots()) return false;
  if (((codec.varying[e.slot / 64] >> (e.slot % 64)) & 1) == 0) return false;  // its default is not 0
  const auto n = static_cast<std::size_t>(sum_stride_);
  if (e.slot < kBeautySums) return !fits_int64(e.value);
  if (e.slot == kBeautySums) return !fits_uint32(e.value) && e.value >> 64 == 0;
  if (e.slot < kBeautySums + 1 + n)
    return sum_kinds_[e.slot - kBeautySums - 1] == kWide64 ? !fits_int64(e.value) : !fits_uint32(e.value);
  uint32_t bits = 0;
  return e.value >> 64 == 0 && !as_float(std::bit_cast<double>(static_cast<uint64_t>(e.value)), bits);
}

bool Film::read_codec(std::istream& in, std::size_t pixels, StateCodec& codec, std::vector<StateException>& out,
                      std::string& error) const {
  // The defaults: a full record whose float slots are plain.
  codec.defaults.assign(record_bytes_, 0);
  if (!in.read(codec.defaults.data(), static_cast<std::streamsize>(record_bytes_))) {
    error = "truncated film state header";
    return false;
  }
  const std::size_t slots = slot_offset_.size(), first_value = slots - static_cast<std::size_t>(value_stride_);
  codec.varying.fill(0);
  for (std::size_t k = 0; k < slots; ++k) {
    const std::size_t at = slot_offset_[k], width = (k + 1 < slots ? slot_offset_[k + 1] : record_bytes_) - at;
    const char* d = codec.defaults.data() + at;
    if (std::all_of(d, d + width, [](char c) { return c == 0; })) codec.varying[k / 64] |= uint64_t{1} << (k % 64);
    uint32_t bits = 0;
    std::memcpy(&bits, d, std::min(width, sizeof bits));
    if (k >= first_value && !plain_float(bits)) {
      error = "corrupt film state (default of slot " + std::to_string(k) + ")";
      return false;
    }
  }
  decode_defaults(codec);
  // The exceptions.
  uint64_t count = 0;
  if (!in.read(reinterpret_cast<char*>(&count), sizeof count)) {
    error = "truncated film state header";
    return false;
  }
  if (count > pixels * state_slots()) {
    error = "film state lists " + std::to_string(count) + " wide values, more than its " +
            std::to_string(pixels * state_slots()) + " slots (corrupt)";
    return false;
  }
  out.clear();
  out.reserve(static_cast<std::size_t>(std::min<uint64_t>(count, 1u << 16)));
  for (uint64_t i = 0; i < count; ++i) {
    char bytes[kExceptionBytes];
    if (!in.read(bytes, sizeof bytes)) {
      error = "truncated film state";
      return false;
    }
    const char* p = bytes;
    StateException e;
    e.pixel = load<uint64_t>(p);
    e.slot = load<uint32_t>(p);
    const auto lo = load<uint64_t>(p), hi = load<uint64_t>(p);
    e.value = (static_cast<UInt128>(hi) << 64) | lo;
    const bool ordered = out.empty() || out.back().pixel < e.pixel ||
                         (out.back().pixel == e.pixel && out.back().slot < e.slot);
    if (!ordered || !valid_exception(e, pixels, codec)) {
      error = "corrupt film state (wide value " + std::to_string(i) + " of " + std::to_string(count) + ")";
      return false;
    }
    out.push_back(e);
  }
  // The record index: group g's records take between a mask and a full
  // record each.
  const std::size_t groups = (pixels + kStateGroup - 1) / kStateGroup;
  codec.index.assign(groups + 1, 0);
  if (!in.read(reinterpret_cast<char*>(codec.index.data()), static_cast<std::streamsize>(codec.index.size() * sizeof(uint64_t)))) {
    error = "truncated film state header";
    return false;
  }
  bool ordered = codec.index[0] == 0;
  for (std::size_t g = 0; g < groups && ordered; ++g) {
    const uint64_t records = std::min(kStateGroup, pixels - g * kStateGroup);
    ordered = codec.index[g + 1] >= codec.index[g] &&
              codec.index[g + 1] - codec.index[g] >= records * bitmap_bytes_ &&
              codec.index[g + 1] - codec.index[g] <= records * (bitmap_bytes_ + record_bytes_);
  }
  if (!ordered) {
    error = "corrupt film state (record index)";
    return false;
  }
  return true;
}

void Film::write_codec(std::ostream& out, const StateCodec& codec, const std::vector<StateException>& exceptions) const {
  out.write(codec.defaults.data(), static_cast<std::streamsize>(codec.defaults.size()));
  const auto count = static_cast<uint64_t>(exceptions.size());
  out.write(reinterpret_cast<const char*>(&count), sizeof count);
  for (const StateException& e : exceptions) {
    char bytes[kExceptionBytes];
    char* p = bytes;
    store(p, e.pixel);
    store(p, e.slot);
    store(p, static_cast<uint64_t>(e.value));
    store(p, static_cast<uint64_t>(e.value >> 64));
    out.write(bytes, sizeof bytes);
  }
  out.write(reinterpret_cast<const char*>(codec.index.data()), static_cast<std::streamsize>(codec.index.size() * sizeof(uint64_t)));
}

}  // namespace pt
