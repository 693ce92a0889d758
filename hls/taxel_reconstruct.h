// taxel_reconstruct: carrier magnitudes of one frame -> taxel conductances,
// one square root per line and one multiply per taxel (thesis §3.2: taxel
// (i, j) = amp(row i) * amp(col j); its geometric mean is the taxel's
// conductance fraction when only that taxel of its row and column is
// pressed). Bit-exact spec of the `taxel_reconstruct` routine of the frame
// engine (rtl/ucode/dtmf_chain.fe) and, in its streaming form
// (TaxelReconstructStream, below), of the block rtl/taxel_reconstruct.v.
//
// Number formats
//   mag_k   unsigned 16 bits (carrier_magnitude units), k = 0..K-1, rows
//           first, then columns.
//   root_k  = isqrt(mag_k << 14) = floor(sqrt(mag_k) * 2^7): UQ8.7, 15 bits
//           (mag < 2^16, so mag << 14 < 2^30 and root < 2^15), exact floor.
//   P_ij    = root_i * root_j: UQ16.14, < 2^30, exact.
//   g_ij    = sat16(round(P_ij * recip >> (recip_shift + 14))): UQ1.15, with
//           recip = round(2^(15 + recip_shift) / F) where F is the magnitude
//           of one full carrier (the builder picks recip_shift so that
//           2^14 <= recip < 2^15: recip is a positive 16-bit signed operand).
//           32768 = one full carrier; saturates at 65535 (~2.0).
// Rounding: round half up ((x + 2^(s-1)) >> s); saturation to 16 bits; no
// intermediate wraps (P * recip < 2^45, held in 64 bits here, 48 in RTL).
// Error against g* = sqrt(mag_i mag_j) / F (real): root_k = 2^7 sqrt(mag_k)
// - e_k with 0 <= e_k < 1, so 2^14 sqrt(mag_i mag_j) - P_ij lies in
// [0, 2^7 (sqrt(mag_i) + sqrt(mag_j))); the recip rounding adds a relative
// 2^-15 and the final rounding half an LSB:
//   |g - 2^15 g*| <= 2^15 (sqrt(m_i) + sqrt(m_j)) / (2^7 F) + 2^-15 g + 1/2.
// (tests/hls/taxel_reconstruct_test.cpp checks it against the golden model.)
#pragma once

#include <cstdint>

#include "hls/isqrt.h"

namespace eskin::hls {

struct TaxelReconstructConfig {
  uint8_t rows = 3, cols = 3;  // 1..R_MAX, 1..C_MAX
  uint16_t recip = 0;          // 1..32767, see above
  uint8_t recip_shift = 0;     // 0..31
};

// Round half up by `s` bits (none for s = 0) and saturate to `bits`.
inline uint32_t round_sat(uint64_t x, int s, int bits) {
  if (s > 0) x = (x + (uint64_t(1) << (s - 1))) >> s;
  const uint64_t max = (uint64_t(1) << bits) - 1u;
  return uint32_t(x > max ? max : x);
}

inline uint16_t taxel_line_root(uint16_t mag) { return uint16_t(isqrt<15>(uint32_t(mag) << 14)); }

inline uint16_t taxel_value(uint16_t root_i, uint16_t root_j, const TaxelReconstructConfig& c) {
  const uint64_t p = uint64_t(uint32_t(root_i) * root_j) * c.recip;
  return uint16_t(round_sat(p, c.recip_shift + 14, 16));
}

template <int R_MAX, int C_MAX>
class TaxelReconstruct {
  static_assert(R_MAX >= 1 && C_MAX >= 1 && R_MAX + C_MAX <= 255, "sizes");

 public:
  using Config = TaxelReconstructConfig;

  // False (old config kept) and the field named on bad input.
  bool configure(const Config& c, const char** bad_field = nullptr) {
    const char* bad = nullptr;
    if (c.rows < 1 || c.rows > R_MAX) bad = "rows (expected 1..R_MAX)";
    else if (c.cols < 1 || c.cols > C_MAX) bad = "cols (expected 1..C_MAX)";
    else if (c.recip < 1 || c.recip > 32767) bad = "recip (expected 1..32767)";
    else if (c.recip_shift > 31) bad = "recip_shift (expected 0..31)";
    if (bad) {
      if (bad_field) *bad_field = bad;
      return false;
    }
    cfg_ = c;
    return true;
  }
  const Config& config() const { return cfg_; }

  // One frame's magnitudes (rows then columns): the line roots.
  void lines(const uint16_t* mag) {
    for (int k = 0; k < cfg_.rows + cfg_.cols; ++k) root_[k] = taxel_line_root(mag[k]);
  }
  uint16_t root(int k) const { return root_[k]; }
  // g of taxel (i, j) from this frame's roots.
  uint16_t value(int i, int j) const { return taxel_value(root_[i], root_[cfg_.rows + j], cfg_); }

 private:
  Config cfg_{};
  uint16_t root_[R_MAX + C_MAX] = {};
};


// Streaming form, element by element (the spec of rtl/taxel_reconstruct.v's
// streams): a frame's magnitudes {k, mag, last} in, one at a time (k is the
// line, rows first; a k >= rows + cols is dropped), then its taxels out
// row-major, one per call, with the ghost filter's active-site mask applied
// as DtmfChain applies it (hls/dtmf_chain.h): `mask` is the site bit after
// GhostFilter::frame, `site` the bit after GhostFilter::release (kept while
// g >= release), and g is 0 off a site when `ghost`.
struct TaxelMagIn {
  uint8_t k = 0;
  uint16_t mag = 0;
  bool last = false;
};

struct TaxelOut {
  uint8_t i = 0, j = 0;
  uint16_t g = 0;     // UQ1.15
  bool site = false;  // mask && g >= release
  bool last = false;  // (rows - 1, cols - 1)
};

template <int R_MAX, int C_MAX>
class TaxelReconstructStream {
 public:
  using Config = TaxelReconstructConfig;
  bool configure(const Config& c, const char** bad_field = nullptr) { return core_.configure(c, bad_field); }
  const Config& config() const { return core_.config(); }

  // One magnitude; true when it closes the frame (its line roots are then
  // this frame's).
  bool push(const TaxelMagIn& in) {
    const Config& c = core_.config();
    if (in.k < c.rows + c.cols) mag_[in.k] = in.mag;
    if (in.last) core_.lines(mag_);
    return in.last;
  }
  // Taxel n (row-major, 0 .. rows cols - 1) of the frame closed last.
  TaxelOut taxel(int n, bool mask, bool ghost, uint16_t release) const {
    const Config& c = core_.config();
    TaxelOut o;
    o.i = uint8_t(n / c.cols);
    o.j = uint8_t(n % c.cols);
    const uint16_t g = core_.value(o.i, o.j);
    o.site = mask && g >= release;
    o.g = (!ghost || o.site) ? g : 0;
    o.last = n == c.rows * c.cols - 1;
    return o;
  }

 private:
  TaxelReconstruct<R_MAX, C_MAX> core_;
  uint16_t mag_[R_MAX + C_MAX] = {};
};

}  // namespace eskin::hls
