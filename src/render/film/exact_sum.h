// ExactSum: a running sum whose value does not depend on the order or the
// grouping of its additions, so that a pixel's samples added in one pass, in
// many passes, or on many machines and then merged give the same bits
// (docs/distributed.md, "Exact sums").
//
// Floating-point addition is not associative: ((a + b) + c) and (a + (b + c))
// can differ in the last bit, so sums of sample ranges added in a different
// grouping would not reproduce a render bit for bit. ExactSum keeps a fixed-
// point number instead: an integer count of 2^-44 units (5.7e-14) in 128-bit
// two's complement. Each term is rounded once, to the nearest unit, when it is
// added; from then on additions are integer additions, exact and associative.
// The film's terms are products of two floats (weight x radiance), exact in
// double, so the rounding is the only loss: at most 2.9e-14 per sample, far
// below what the float image can show.
//
// Range: a term's magnitude is clamped to 2^51 (2.3e15; a sample that bright is
// a firefly many orders beyond any scene's light), so 2^32 terms, more than the
// sample indices (int) can number, cannot overflow.
#pragma once

#include <cmath>
#include <cstdint>

namespace pt {

// 128-bit integers (a GCC and Clang extension; __extension__ keeps -Wpedantic quiet).
__extension__ typedef __int128 Int128;
__extension__ typedef unsigned __int128 UInt128;

class ExactSum {
 public:
  static constexpr int kFractionBits = 44;
  static constexpr double kUnit = 0x1p-44;     // the value of one unit
  static constexpr double kMaxTerm = 0x1p51;  // terms are clamped to +-this

  ExactSum() = default;
  // The sum holding `value` alone (rounded to a unit); implicit, so that sums
  // can be written as numbers in tests.
  ExactSum(double value) { add(value); }  // NOLINT(google-explicit-constructor)

  void add(double term) { set_raw(raw() + to_units(term)); }
  void add(const ExactSum& o) { set_raw(raw() + o.raw()); }
  // The sum as a double (rounded to nearest from the exact integer).
  // A sum that fits in 64 bits (every pixel's but the brightest) converts
  // from int64, which rounds as the 128-bit conversion does (a libgcc call).
  double value() const {
    const auto low = static_cast<int64_t>(lo_);
    if (hi_ == static_cast<uint64_t>(low >> 63)) return static_cast<double>(low) * kUnit;
    return static_cast<double>(static_cast<Int128>(raw())) * kUnit;
  }
  bool is_zero() const { return lo_ == 0 && hi_ == 0; }
  bool operator==(const ExactSum&) const = default;

  // The integer, as unsigned (wrapping) arithmetic: two's complement.
  UInt128 raw() const { return (static_cast<UInt128>(hi_) << 64) | lo_; }
  void set_raw(UInt128 v) {
    lo_ = static_cast<uint64_t>(v);
    hi_ = static_cast<uint64_t>(v >> 64);
  }

  // `term` in units, rounded to nearest (ties to even); NaN counts as 0 (the
  // film never adds one: non-finite samples are added as black).
  static UInt128 to_units(double term) {
    constexpr double kFast = 0x1p18;  // |term| * 2^44 < 2^62: one int64 conversion
    if (std::fabs(term) < kFast) return static_cast<UInt128>(static_cast<Int128>(std::llrint(term * 0x1p44)));
    if (std::isnan(term)) return 0;
    const double t = std::fmax(-kMaxTerm, std::fmin(kMaxTerm, term));
    const double whole = std::trunc(t);  // exact: |t| <= 2^51
    const Int128 units = static_cast<Int128>(static_cast<int64_t>(whole)) * (Int128{1} << kFractionBits) +
                           std::llrint((t - whole) * 0x1p44);  // t - whole is exact
    return static_cast<UInt128>(units);
  }

 private:
  // Two 64-bit halves (not an Int128 member) keep the type 8-byte aligned:
  // a PixelSum has no padding, so the film state is written as it is in memory.
  uint64_t lo_ = 0;
  uint64_t hi_ = 0;
};

}  // namespace pt
