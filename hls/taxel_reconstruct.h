// Taxel reconstruction: carrier magnitudes of one frame -> taxel values.
// Bit-exact spec of rtl/taxel_reconstruct.v (thesis §3.2: taxel (i, j) =
// amp(row i) * amp(col j)).
//
// Input tokens {k, mag}: per frame K = rows + cols tokens, rows first (k <
// rows), then columns; the token with k == K-1 closes the frame. mag is
// unsigned MAG_W bits (<= 16) in the units of carrier_magnitude (DFT window
// sum, possibly >> a stated shift). Tokens are stored by k, so order inside
// a frame does not matter, only that k == K-1 comes last.
//
// Activity mask ("taxels only where rows and columns are active"): line k is
// active when mag_k >= cfg.active_threshold (0: every line active). Only
// active rows x active columns are computed and emitted, row-major, so an
// idle skin costs K+1 cycles per frame and emits nothing.
//
// Output tokens {row, col, value, last}, value unsigned TAX_W bits (<= 32),
// last on the frame's final taxel. Modes (m_i row, m_j column magnitude):
//  Product:     P = m_i * m_j exactly (2*MAG_W bits); value = sat(round(P >> shift))
//  Conductance: r = isqrt(P) = floor(sqrt(P)) (geometric mean, MAG_W bits);
//               g = sat16(round(r * recip >> recip_shift)): with recip =
//               round(2^(15+recip_shift) / full_carrier), g is UQ1.15 (1.0 =
//               one full carrier; saturates at 0xFFFF ~ 2.0); value = sat(g)
//  Pressure:    g as above, then the piecewise-linear table (PWL_N = 16
//               entries, g_tab ascending, g_tab[0] = 0):
//               s = max{s : g_tab[s] <= g} (4-step binary search),
//               value = sat(p_tab[s] + round((g - g_tab[s]) * slope[s] >> slope_shift)).
//               Unused entries are padded by the builder (g 0xFFFF, slope 0).
// Rounding: round half up, adding 1 << (s-1) before >> s (none when s = 0).
// Saturation: to the result width (16 bits for g, TAX_W for value); all
// intermediates are wide enough that nothing wraps (P: 32 bits, sums: 33).
//
// Timing of the RTL (always-ready output; intended II, asserted in tests):
// one input token per cycle (K cycles), then 1 START cycle, then each taxel
// takes c cycles, c = 1 (Product), MAG_W + 2 (Conductance), MAG_W + 7
// (Pressure: SQRT MAG_W, GSCALE 1, SEARCH 4, INTERP 1, OUT 1). Frame period =
// K + 1 + T * c cycles with T = active rows * active cols; taxel n (0-based)
// leaves at cycle t_last_in + 1 + (n + 1) * c. One multiplier (16x16) is
// shared by m_i*m_j, r*recip and (g - g_tab)*slope.
#pragma once

#include <cstdint>

#include "hls/isqrt.h"

namespace eskin::hls {

enum class TaxelMode : uint8_t { Product = 0, Conductance = 1, Pressure = 2 };

constexpr int kTaxelPwlN = 16;

struct TaxelReconstructConfig {
  uint8_t rows = 3, cols = 3;       // 1..R_MAX, 1..C_MAX
  TaxelMode mode = TaxelMode::Product;
  uint8_t shift = 0;                // Product: value = round(P >> shift), 0..31
  uint16_t active_threshold = 0;    // line active when mag >= this
  uint16_t recip = 0;               // Conductance/Pressure: UQ(recip_shift - 15) scale
  uint8_t recip_shift = 0;          // 0..31
  uint8_t slope_shift = 0;          // 0..31
  uint16_t g_tab[kTaxelPwlN] = {};  // UQ1.15 breakpoints, ascending, g_tab[0] = 0
  uint32_t p_tab[kTaxelPwlN] = {};  // value at each breakpoint (TAX_W bits)
  uint16_t slope[kTaxelPwlN] = {};  // value LSB per g LSB, << slope_shift
};

struct MagToken { uint8_t k; uint16_t mag; };
struct TaxelToken { uint8_t row, col; uint32_t value; bool last; };

// Round half up by `s` bits (none for s = 0) and saturate to `bits`.
inline uint32_t round_sat(uint64_t x, int s, int bits) {
  if (s > 0) x = (x + (uint64_t(1) << (s - 1))) >> s;
  const uint64_t max = (uint64_t(1) << bits) - 1u;
  return uint32_t(x > max ? max : x);
}

template <int R_MAX, int C_MAX, int MAG_W = 16, int TAX_W = 16>
class TaxelReconstruct {
  static_assert(R_MAX >= 1 && C_MAX >= 1 && R_MAX + C_MAX <= 255, "sizes");
  static_assert(MAG_W >= 1 && MAG_W <= 16, "MAG_W <= 16: one 16x16 multiplier");
  static_assert(TAX_W >= 1 && TAX_W <= 32, "TAX_W <= 32");

 public:
  using Config = TaxelReconstructConfig;

  // Returns false (and keeps the old config) when a field is out of range;
  // `bad_field` then names it.
  bool configure(const Config& c, const char** bad_field = nullptr) {
    const char* bad = nullptr;
    if (c.rows < 1 || c.rows > R_MAX) bad = "rows (expected 1..R_MAX)";
    else if (c.cols < 1 || c.cols > C_MAX) bad = "cols (expected 1..C_MAX)";
    else if (c.mode != TaxelMode::Product && c.mode != TaxelMode::Conductance &&
             c.mode != TaxelMode::Pressure) bad = "mode (expected 0..2)";
    else if (c.shift > 31 || c.recip_shift > 31 || c.slope_shift > 31)
      bad = "shift/recip_shift/slope_shift (expected 0..31)";
    else if (c.mode == TaxelMode::Pressure && c.g_tab[0] != 0) bad = "g_tab[0] (expected 0)";
    else if (c.active_threshold >> MAG_W) bad = "active_threshold (expected < 2^MAG_W)";
    for (int s = 1; !bad && c.mode == TaxelMode::Pressure && s < kTaxelPwlN; ++s)
      if (c.g_tab[s] < c.g_tab[s - 1]) bad = "g_tab (expected ascending)";
    for (int s = 0; !bad && TAX_W < 32 && s < kTaxelPwlN; ++s)
      if (c.p_tab[s] >> (TAX_W % 32)) bad = "p_tab (expected < 2^TAX_W)";
    if (bad) { if (bad_field) *bad_field = bad; return false; }
    cfg_ = c;
    n_out_ = head_ = 0;
    return true;
  }
  const Config& config() const { return cfg_; }

  // One magnitude token. Returns true when it closed a frame; that frame's
  // taxels are then available from pop(). Tokens with k >= K are ignored.
  bool push(const MagToken& t) {
    const int K = cfg_.rows + cfg_.cols;
    if (t.k >= K) return false;
    mag_[t.k] = uint16_t(t.mag & ((1u << MAG_W) - 1u));
    if (t.k != K - 1) return false;
    compute_frame();
    return true;
  }
  bool pop(TaxelToken& out) {
    if (head_ >= n_out_) return false;
    out = out_[head_++];
    return true;
  }
  int pending() const { return n_out_ - head_; }
  int active_rows() const { return act_r_; }
  int active_cols() const { return act_c_; }

  // One taxel from its row and column magnitudes (also usable on its own).
  uint32_t taxel(uint32_t mi, uint32_t mj) const {
    const uint32_t p = mi * mj;  // < 2^32: MAG_W <= 16
    if (cfg_.mode == TaxelMode::Product) return round_sat(p, cfg_.shift, TAX_W);
    const uint32_t r = isqrt<MAG_W>(p);
    const uint32_t g = round_sat(uint64_t(r) * cfg_.recip, cfg_.recip_shift, 16);
    if (cfg_.mode == TaxelMode::Conductance) return round_sat(g, 0, TAX_W);
    int s = 0;  // binary search, 4 steps: largest s with g_tab[s] <= g
    for (int b = kTaxelPwlN / 2; b > 0; b >>= 1)
      if (cfg_.g_tab[s + b] <= g) s += b;
    const uint64_t d = uint64_t(g - cfg_.g_tab[s]) * cfg_.slope[s];
    const uint64_t half = cfg_.slope_shift ? (uint64_t(1) << (cfg_.slope_shift - 1)) : 0;
    return round_sat(uint64_t(cfg_.p_tab[s]) + ((d + half) >> cfg_.slope_shift), 0, TAX_W);
  }

  // Cycles per taxel of the RTL in this mode (see the header comment).
  int cycles_per_taxel() const {
    switch (cfg_.mode) {
      case TaxelMode::Product: return 1;
      case TaxelMode::Conductance: return MAG_W + 2;
      default: return MAG_W + 7;
    }
  }

 private:
  void compute_frame() {
    bool row_on[R_MAX], col_on[C_MAX];
    act_r_ = act_c_ = 0;
    for (int i = 0; i < cfg_.rows; ++i)
      act_r_ += (row_on[i] = mag_[i] >= cfg_.active_threshold);
    for (int j = 0; j < cfg_.cols; ++j)
      act_c_ += (col_on[j] = mag_[cfg_.rows + j] >= cfg_.active_threshold);
    n_out_ = head_ = 0;
    for (int i = 0; i < cfg_.rows; ++i) {
      if (!row_on[i]) continue;
      for (int j = 0; j < cfg_.cols; ++j) {
        if (!col_on[j]) continue;
        out_[n_out_++] = TaxelToken{uint8_t(i), uint8_t(j),
                                    taxel(mag_[i], mag_[cfg_.rows + j]), false};
      }
    }
    if (n_out_ > 0) out_[n_out_ - 1].last = true;
  }

  Config cfg_{};
  uint16_t mag_[R_MAX + C_MAX] = {};
  TaxelToken out_[R_MAX * C_MAX] = {};
  int n_out_ = 0, head_ = 0, act_r_ = 0, act_c_ = 0;
};

}  // namespace eskin::hls
