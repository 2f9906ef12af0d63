// A sum of floats that comes out the same in any order: every term is
// converted exactly to a 128-bit fixed-point number (64 fractional bits) and
// added as an integer, and integer addition is associative. So a film
// rendered in pieces (checkpoints, --part shares, MPI ranks) and added up
// equals, bit for bit, the film rendered in one go, whatever the pieces and
// whoever adds them.
//
// Range: a term's magnitude must stay below 2^62 (about 4.6e18; the film
// treats larger terms like non-finite ones); terms below 2^-41 lose low
// bits, truncated toward zero (under 2^-64 each). The integers add modulo
// 2^128 (two's complement, no overflow checks on the hot path): exact, and
// so order-independent, always; the value is right while the true sum stays
// below 2^63, which takes over 2^64 terms of the largest size.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace lantern {

class FixedSum {
 public:
  using Raw = __int128;  // two's complement; stored and added as unsigned
  static constexpr int kFractionBits = 64;
  static constexpr float kMaxTerm = 4.6e18f;  // below 2^62

  // Whether x can be added: finite and below kMaxTerm in magnitude.
  static bool addable(float x) { return x > -kMaxTerm && x < kMaxTerm; }

  // x * 2^64 as an integer, exact for |x| >= 2^-41, from the float's bits;
  // out-of-range terms give +-2^126 (callers check addable()).
  static Raw to_fixed(float x) {
    const uint32_t bits = std::bit_cast<uint32_t>(x);
    const int exponent = int((bits >> 23) & 0xFFu);
    if (exponent == 0) return 0;                                     // zero and denormals (below 2^-126)
    if (exponent > 188) return (bits >> 31) ? -kLargest : kLargest;  // 2^62 and up, Inf, NaN
    const Raw mantissa = Raw((bits & 0x7FFFFFu) | 0x800000u);
    // x = mantissa * 2^(exponent - 150); shifted into 64 fractional bits.
    const int shift = exponent - 150 + kFractionBits;
    Raw v = shift >= 0 ? mantissa << shift : (shift > -24 ? mantissa >> -shift : Raw(0));
    return (bits >> 31) ? -v : v;
  }

  void add(float x) { add_raw(to_fixed(x)); }
  // For sums of terms that are not negative (guiding/directional_tree.h):
  // past the largest value (2^63) the sum stays there. Partial sums of such
  // terms only grow, so the result, min(the true sum, 2^63), is still the
  // same in any order. A term beyond kMaxTerm counts as kMaxTerm.
  // (Terms that are not positive, NaN too, add nothing: these sums hold
  // none.)
  void add_saturating(float x) {
    if (x > 0.f) add_saturating(of_raw(to_fixed(std::min(x, kMaxTerm))));
  }
  void add_saturating(const FixedSum& other) {
    const Bits sum = raw_ + other.raw_;
    raw_ = Raw(sum) < 0 ? Bits(kMost) : sum;
  }
  static FixedSum of_raw(Raw r) {
    FixedSum s;
    s.raw_ = Bits(r);
    return s;
  }
  void add(const FixedSum& other) { raw_ += other.raw_; }
  void add_raw(Raw v) { raw_ += Bits(v); }  // modulo 2^128

  double value() const {
    // High and low halves converted separately: the high half exactly, the
    // low half to within one ulp of the result.
    const int64_t hi = int64_t(uint64_t(raw_ >> 64));
    const uint64_t lo = uint64_t(raw_);
    return double(hi) + double(lo) * 0x1p-64;
  }

  Raw raw() const { return Raw(raw_); }
  // A count as a sum (its value n), and back: counts add up across
  // processes with the sums they counted.
  static FixedSum of_count(uint64_t n) {
    FixedSum s;
    s.raw_ = Bits(n) << kFractionBits;
    return s;
  }
  uint64_t count() const { return uint64_t(raw_ >> kFractionBits); }
  // Whether this can be a sum of terms that are not negative: its value
  // at least zero and below 2^63, the range it is right in (what a
  // checkpoint's bytes must be).
  bool sane_total() const { return raw() >= 0; }

 private:
  using Bits = unsigned __int128;
  static constexpr Raw kLargest = Raw(1) << 126;
  static constexpr Raw kMost = Raw(~(Bits(1) << 127));  // 2^127 - 1

  Bits raw_ = 0;
};

// Sums kept as bytes, 16 per sum (FixedSum::raw, little-endian), as
// processes exchange them: adds `more`'s to `total`'s place by place,
// saturating (the guiding field's sums: none is negative). Both must hold
// the same number of sums (std::runtime_error otherwise).
inline void add_saturating_sums(std::string& total, const std::string& more) {
  if (total.size() != more.size())
    throw std::runtime_error("sums of " + std::to_string(more.size()) + " bytes added to sums of " +
                             std::to_string(total.size()));
  for (size_t at = 0; at + sizeof(FixedSum::Raw) <= total.size(); at += sizeof(FixedSum::Raw)) {
    FixedSum::Raw a, b;
    std::memcpy(&a, total.data() + at, sizeof a);
    std::memcpy(&b, more.data() + at, sizeof b);
    FixedSum sum = FixedSum::of_raw(a);
    sum.add_saturating(FixedSum::of_raw(b));
    a = sum.raw();
    std::memcpy(total.data() + at, &a, sizeof a);
  }
}

}  // namespace lantern
