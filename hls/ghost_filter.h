// Multi-touch ghost correction by active-site tracking (thesis §5.2), in
// integer form. Bit-exact spec of rtl/ghost_filter.v. Same algorithm as the
// golden host/golden/ghost_filter.h, except where noted (*).
//
// Input tokens {k, mag} as in hls/taxel_reconstruct.h: per frame K = rows +
// cols magnitudes (unsigned MAG_W bits, rows first), in order k = 0..K-1;
// k == K-1 closes the frame. Thresholds are in the same magnitude units
// (the config builder in the test turns golden's g-unit thresholds into
// these: onset_mag = floor(onset*F), tol = floor(pair_tol*F),
// release2 = ceil((release*F)^2), F = magnitude of one full carrier).
//
// Per frame:
//  1. rise_k = mag_k - mag_k(lookback frames ago) (history starts at 0; a
//     ring of lookback x K magnitudes); rem_k = rise_k if rise_k > onset else 0.
//  2. thesis mode: the first row and the first column with the largest rem
//     (if both > 0) make an active site (nothing if it already is).
//     improved mode (*): greedy pairing by matching rise magnitudes: take the
//     largest remaining row rem and column rem (first index on ties); while
//     both > pair_tol, pair them as a candidate site and subtract the smaller
//     from both. If afterwards every line's rem <= pair_tol, all candidates
//     become active sites; else the thesis step above is used.
//     (*) golden searches the smallest fitting set exhaustively and solves
//     site values jointly (NNLS). Greedy pairing finds the same sites when
//     rises are distinct and lines not shared by simultaneous onsets; the
//     joint NNLS value solve is left to the host.
//  3. release: each site (row-major) with mag_i * mag_j < release2, i.e.
//     sqrt(r_i c_j) < release, is removed.
//  4. emit the remaining sites row-major as {row, col, value, last}:
//     Product:     value = sat(round(mag_i*mag_j >> shift))  (TAX_W bits)
//     Conductance: value = sat(g), g = sat16(round(isqrt(P)*recip >> recip_shift))
//                  (UQ1.15 with recip from set_full_carrier()).
// Rounding half up; saturation to the result width; no wrap anywhere.
//
// Timing of the RTL with out_ready = 1 (asserted in tests): K input cycles,
// 1 FLUSH (last history read), 1 DECIDE, P+1 per greedy pairing step (a
// rescan of rows and columns in parallel, P = max(rows, cols), + DECIDE),
// when the pairing fits, 1 cycle per pair to commit it (steps), 1 + S_b
// release cycles (S_b sites before release), 1 + S_a*c emit cycles (S_a
// sites emitted; c = 1 Product, MAG_W+2 Conductance). Frame period =
// K + 4 + steps*(P+1) + (fit ? steps : 0) + S_b + S_a*c; steps <= rising
// lines - 1.
#pragma once

#include <cstdint>

#include "hls/isqrt.h"
#include "hls/taxel_reconstruct.h"  // MagToken, TaxelToken, round_sat

namespace eskin::hls {

struct GhostFilterConfig {
  uint8_t rows = 3, cols = 3;   // 1..R_MAX, 1..C_MAX
  uint16_t lookback = 32;       // 1..L_MAX frames
  bool improved = true;         // greedy pairing (else thesis §5.2 step)
  uint16_t onset = 0;           // rise > onset starts a site (mag units)
  uint16_t pair_tol = 0;        // improved: max rem a pairing may leave
  uint32_t release2 = 0;        // site kept while mag_i * mag_j >= release2
  bool conductance = false;     // value: g (true) or the product (false)
  uint8_t shift = 0;            // Product: >> shift, 0..31
  uint16_t recip = 0;           // Conductance: as in taxel_reconstruct
  uint8_t recip_shift = 0;      // 0..31
};

template <int R_MAX, int C_MAX, int L_MAX, int MAG_W = 16, int TAX_W = 16>
class GhostFilter {
  static_assert(R_MAX >= 1 && C_MAX >= 1 && R_MAX + C_MAX <= 255 && L_MAX >= 1, "sizes");
  static_assert(MAG_W >= 1 && MAG_W <= 16 && TAX_W >= 1 && TAX_W <= 32, "widths");
  static constexpr int K_MAX = R_MAX + C_MAX;

 public:
  using Config = GhostFilterConfig;

  // Returns false (keeping the old config) and names the field on bad input.
  // A new config clears the history and the sites.
  bool configure(const Config& c, const char** bad_field = nullptr) {
    const char* bad = nullptr;
    if (c.rows < 1 || c.rows > R_MAX) bad = "rows (expected 1..R_MAX)";
    else if (c.cols < 1 || c.cols > C_MAX) bad = "cols (expected 1..C_MAX)";
    else if (c.lookback < 1 || c.lookback > L_MAX) bad = "lookback (expected 1..L_MAX)";
    else if (c.shift > 31 || c.recip_shift > 31) bad = "shift/recip_shift (expected 0..31)";
    else if ((c.onset >> MAG_W) || (c.pair_tol >> MAG_W))
      bad = "onset/pair_tol (expected < 2^MAG_W)";
    if (bad) { if (bad_field) *bad_field = bad; return false; }
    cfg_ = c;
    reset();
    return true;
  }
  void reset() {
    for (auto& slot : hist_)
      for (auto& h : slot) h = 0;
    for (auto& r : site_)
      for (auto& s : r) s = false;
    head_ = n_out_ = rd_ = 0;
  }

  // One magnitude token; true when it closed a frame (its sites can then be
  // popped). Tokens with k >= K are ignored.
  bool push(const MagToken& t) {
    const int K = cfg_.rows + cfg_.cols;
    if (t.k >= K) return false;
    const uint16_t m = uint16_t(t.mag & ((1u << MAG_W) - 1u));
    const int32_t rise = int32_t(m) - int32_t(hist_[head_][t.k]);
    hist_[head_][t.k] = m;
    mag_[t.k] = m;
    rem_[t.k] = rise > int32_t(cfg_.onset) ? uint16_t(rise) : 0;
    if (t.k != K - 1) return false;
    head_ = head_ + 1 == cfg_.lookback ? 0 : head_ + 1;
    frame();
    return true;
  }
  bool pop(TaxelToken& out) {
    if (rd_ >= n_out_) return false;
    out = out_[rd_++];
    return true;
  }
  bool site(int i, int j) const { return site_[i][j]; }
  // Of the last frame: greedy pairing steps, sites before / after release.
  int pair_steps() const { return steps_; }
  bool pairing_fit() const { return fit_; }  // improved mode: candidates committed
  int sites_before_release() const { return s_before_; }
  int sites_after_release() const { return n_out_; }

 private:
  // First (lowest index) largest rem among rows, and among columns.
  void argmax(int& r, int& c) const {
    r = 0; c = 0;
    for (int i = 1; i < cfg_.rows; ++i) if (rem_[i] > rem_[r]) r = i;
    for (int j = 1; j < cfg_.cols; ++j) if (rem_[cfg_.rows + j] > rem_[cfg_.rows + c]) c = j;
  }
  void frame() {
    const int R = cfg_.rows, C = cfg_.cols;
    int br, bc;
    argmax(br, bc);
    const bool thesis_ok = rem_[br] > 0 && rem_[R + bc] > 0;
    bool paired = false;
    steps_ = 0;
    fit_ = false;
    if (cfg_.improved) {
      bool pend[R_MAX][C_MAX] = {};
      int r = br, c = bc;
      while (rem_[r] > cfg_.pair_tol && rem_[R + c] > cfg_.pair_tol) {
        const uint16_t f = rem_[r] < rem_[R + c] ? rem_[r] : rem_[R + c];
        rem_[r] = uint16_t(rem_[r] - f);
        rem_[R + c] = uint16_t(rem_[R + c] - f);
        pend[r][c] = true;
        ++steps_;
        argmax(r, c);
      }
      paired = fit_ = rem_[r] <= cfg_.pair_tol && rem_[R + c] <= cfg_.pair_tol;
      if (paired)
        for (int i = 0; i < R; ++i)
          for (int j = 0; j < C; ++j) site_[i][j] = site_[i][j] || pend[i][j];
    }
    if (!paired && thesis_ok) site_[br][bc] = true;
    // release, then emit (two passes: `last` must be known when emitting)
    s_before_ = n_out_ = rd_ = 0;
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < C; ++j) {
        if (!site_[i][j]) continue;
        ++s_before_;
        if (uint32_t(mag_[i]) * mag_[R + j] < cfg_.release2) site_[i][j] = false;
      }
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < C; ++j)
        if (site_[i][j]) out_[n_out_++] = TaxelToken{uint8_t(i), uint8_t(j), value(mag_[i], mag_[R + j]), false};
    if (n_out_ > 0) out_[n_out_ - 1].last = true;
  }
  uint32_t value(uint32_t mi, uint32_t mj) const {
    const uint32_t p = mi * mj;
    if (!cfg_.conductance) return round_sat(p, cfg_.shift, TAX_W);
    const uint32_t g = round_sat(uint64_t(isqrt<MAG_W>(p)) * cfg_.recip, cfg_.recip_shift, 16);
    return round_sat(g, 0, TAX_W);
  }

  Config cfg_{};
  uint16_t hist_[L_MAX][K_MAX] = {};
  uint16_t mag_[K_MAX] = {}, rem_[K_MAX] = {};
  bool site_[R_MAX][C_MAX] = {};
  TaxelToken out_[R_MAX * C_MAX] = {};
  int head_ = 0, n_out_ = 0, rd_ = 0, steps_ = 0, s_before_ = 0;
  bool fit_ = false;
};

}  // namespace eskin::hls
