// The film state's compact pixel records (version 5; the layout is in
// film_state.cpp): every slot of a pixel in the narrowest type that holds the
// values a render makes, and the rare slot that does not fit in an exception
// list with its full value. Exact either way: a state decodes to the very
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
#include <cstring>
#include <istream>
#include <string>
#include <vector>

#include "render/film/film.h"

namespace pt {
namespace {

enum SlotKind : uint8_t { kWide64, kNarrow32, kFloat32 };  // int64 sum; uint32 id or count; float value

constexpr std::size_t kBeautySums = 5;  // r, g, b, weight, coverage
constexpr std::size_t kBeautyBytes = kBeautySums * sizeof(int64_t) + sizeof(uint32_t);
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
  sum_kinds_.assign(static_cast<std::size_t>(sum_stride_), kWide64);
  for (const SumRun& run : sum_runs_)
    for (int k = 0; k < run.ranks; ++k) sum_kinds_[static_cast<std::size_t>(run.offset + 2 * k)] = kNarrow32;
  record_bytes_ = kBeautyBytes + static_cast<std::size_t>(value_stride_) * sizeof(float);
  for (uint8_t kind : sum_kinds_) record_bytes_ += kind == kWide64 ? sizeof(int64_t) : sizeof(uint32_t);
  kind_runs_.clear();
  for (uint8_t kind : sum_kinds_) {
    if (kind_runs_.empty() || kind_runs_.back().first != kind) kind_runs_.emplace_back(kind, 0);
    ++kind_runs_.back().second;
  }
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

bool Film::decode_record(const char* in, const StateException* ex, const StateException* ex_end, PixelSum& p,
                         ExactSum* sums, double* values) const {
  const char* const record = in;
  ExactSum* beauty[kBeautySums] = {&p.r, &p.g, &p.b, &p.weight, &p.coverage};
  for (ExactSum* b : beauty) *b = from_int64(load<int64_t>(in));
  p.samples = load<uint32_t>(in);
  const auto n = static_cast<std::size_t>(sum_stride_), m = static_cast<std::size_t>(value_stride_);
  ExactSum* to = sums;
  for (const auto& [kind, count] : kind_runs_) {  // runs of one kind: no branch per slot
    if (kind == kWide64) {
      for (int k = 0; k < count; ++k) *to++ = from_int64(load<int64_t>(in));
    } else {
      for (int k = 0; k < count; ++k) (to++)->set_raw(load<uint32_t>(in));
    }
  }
  bool plain = true;
  for (std::size_t k = 0; k < m; ++k) {
    const auto bits = load<uint32_t>(in);
    plain = plain && plain_float(bits);
    values[k] = static_cast<double>(std::bit_cast<float>(bits));
  }
  if (!plain) return false;
  // The exceptions' slots hold 0 in the record; their values replace them.
  for (const StateException* e = ex; e != ex_end; ++e) {
    std::size_t at = 0, width = sizeof(int64_t);  // the slot's place in the record
    const uint32_t slot = e->slot;
    if (slot < kBeautySums) {
      at = slot * sizeof(int64_t);
      beauty[slot]->set_raw(e->value);
    } else if (slot == kBeautySums) {
      at = kBeautySums * sizeof(int64_t);
      width = sizeof(uint32_t);
      p.samples = static_cast<uint64_t>(e->value);
    } else if (slot < kBeautySums + 1 + n) {
      const std::size_t k = slot - kBeautySums - 1;
      at = kBeautyBytes;
      for (std::size_t j = 0; j < k; ++j) at += sum_kinds_[j] == kWide64 ? sizeof(int64_t) : sizeof(uint32_t);
      if (sum_kinds_[k] != kWide64) width = sizeof(uint32_t);
      sums[k].set_raw(e->value);
    } else {
      const std::size_t k = slot - kBeautySums - 1 - n;
      at = record_bytes_ - (m - k) * sizeof(float);
      width = sizeof(float);
      values[k] = std::bit_cast<double>(static_cast<uint64_t>(e->value));
    }
    if (std::any_of(record + at, record + at + width, [](char c) { return c != 0; })) return false;
  }
  return true;
}

bool Film::valid_exception(const StateException& e, std::size_t pixels) const {
  if (e.pixel >= pixels || e.slot >= state_slots()) return false;
  const auto n = static_cast<std::size_t>(sum_stride_);
  if (e.slot < kBeautySums) return !fits_int64(e.value);
  if (e.slot == kBeautySums) return !fits_uint32(e.value) && e.value >> 64 == 0;
  if (e.slot < kBeautySums + 1 + n)
    return sum_kinds_[e.slot - kBeautySums - 1] == kWide64 ? !fits_int64(e.value) : !fits_uint32(e.value);
  uint32_t bits = 0;
  return e.value >> 64 == 0 && !as_float(std::bit_cast<double>(static_cast<uint64_t>(e.value)), bits);
}

bool Film::read_exceptions(std::istream& in, std::size_t pixels, std::vector<StateException>& out,
                           std::string& error) const {
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
    if (!ordered || !valid_exception(e, pixels)) {
      error = "corrupt film state (wide value " + std::to_string(i) + " of " + std::to_string(count) + ")";
      return false;
    }
    out.push_back(e);
  }
  return true;
}

void Film::write_exceptions(std::ostream& out, const std::vector<StateException>& exceptions) {
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
}

}  // namespace pt
