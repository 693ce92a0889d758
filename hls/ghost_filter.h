// ghost_filter: multi-touch ghost correction by active-site tracking (thesis
// §5.2), in integer form. Bit-exact spec of the `ghost_filter` routine of
// the frame engine (rtl/ucode/dtmf_chain.fe). Same algorithm as the golden
// host/golden/ghost_filter.h, except where noted (*).
//
// Input per frame: the K = rows + cols carrier magnitudes (unsigned 16 bits,
// rows first). Thresholds: onset and pair_tol in magnitude units (the
// builder turns golden's g-unit thresholds into them: floor(x * F), F = one
// full carrier's magnitude), release in taxel units (UQ1.15, ceil(x 2^15)).
//
// frame(mag):
//  1. rise_k = mag_k - mag_k(lookback frames ago) (history starts at 0: a
//     ring of lookback x K magnitudes); rem_k = rise_k if rise_k > onset
//     else 0.
//  2. greedy pairing by matching rises (*): take the largest remaining row
//     rem and column rem (first index on ties); while both > pair_tol and
//     fewer than max_pairs candidates are paired, pair them as a candidate
//     site and subtract the smaller from both. Each pair empties a line (its
//     rem reaches 0, and an empty line is never the largest again while the
//     loop goes on), so a frame takes up to R + C - 1 pairs without the cap;
//     max_pairs (the onsets one frame may pair) keeps the frame engine's
//     proven bound independent of the skin's size. If afterwards every
//     line's rem <= pair_tol, all candidates become active sites; else the
//     thesis step: the first row and the first column with
//     the largest rem (both > 0) make an active site (nothing if it already
//     is). The thesis step alone (golden's simultaneous = false) is not a
//     mode here: the top has no way to select it (no scene key, plan field
//     or command), so the spec holds only what the microcode runs.
//     (*) golden searches the smallest fitting set exhaustively, defers
//     ambiguous pairings and solves site values jointly (NNLS). Greedy
//     pairing finds the same sites when rises differ by more than pair_tol
//     and simultaneous onsets do not share lines: on the default scene and
//     the 10x10 scene it gives no ghost frame and misses no touch
//     (tests/hls/dtmf_chain_test.cpp).
// release(value): every active site (row-major) whose taxel value (from
//     taxel_reconstruct, UQ1.15) is below `release` is removed.
// Comparisons and subtractions only: magnitudes and rises fit 17 bits.
#pragma once

#include <cstdint>

namespace eskin::hls {

struct GhostFilterConfig {
  uint8_t rows = 3, cols = 3;   // 1..R_MAX, 1..C_MAX
  uint16_t lookback = 1;        // 1..L_MAX frames
  uint16_t onset = 0;           // rise > onset starts a site (magnitude units)
  uint16_t pair_tol = 0;        // max rem a pairing may leave (magnitude units)
  uint16_t release = 0;         // site kept while its taxel value >= release (UQ1.15)
  uint8_t max_pairs = 8;        // 1..255: candidate pairs a frame may make (step 2)
};

template <int R_MAX, int C_MAX, int L_MAX>
class GhostFilter {
  static_assert(R_MAX >= 1 && C_MAX >= 1 && R_MAX + C_MAX <= 255 && L_MAX >= 1, "sizes");
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
    else if (c.max_pairs < 1) bad = "max_pairs (expected 1..255)";
    if (bad) {
      if (bad_field) *bad_field = bad;
      return false;
    }
    cfg_ = c;
    reset();
    return true;
  }
  // Thresholds may change at run time (SET_THRESHOLD) without a reset.
  void set_thresholds(uint16_t onset, uint16_t pair_tol, uint16_t release) {
    cfg_.onset = onset;
    cfg_.pair_tol = pair_tol;
    cfg_.release = release;
  }
  void reset() {
    for (auto& slot : hist_)
      for (auto& h : slot) h = 0;
    for (auto& r : site_)
      for (auto& s : r) s = false;
    head_ = 0;
  }
  const Config& config() const { return cfg_; }

  // Steps 1-2 for one frame of magnitudes (rows then columns).
  void frame(const uint16_t* mag) {
    const int R = cfg_.rows, K = cfg_.rows + cfg_.cols;
    for (int k = 0; k < K; ++k) {
      const int32_t rise = int32_t(mag[k]) - int32_t(hist_[head_][k]);
      hist_[head_][k] = mag[k];
      rem_[k] = rise > int32_t(cfg_.onset) ? uint16_t(rise) : 0;
    }
    head_ = head_ + 1 == cfg_.lookback ? 0 : head_ + 1;
    int br, bc;
    argmax(br, bc);
    const bool thesis_ok = rem_[br] > 0 && rem_[R + bc] > 0;
    steps_ = 0;
    bool pend[R_MAX][C_MAX] = {};
    int r = br, c = bc;
    while (steps_ < cfg_.max_pairs && rem_[r] > cfg_.pair_tol && rem_[R + c] > cfg_.pair_tol) {
      const uint16_t f = rem_[r] < rem_[R + c] ? rem_[r] : rem_[R + c];
      rem_[r] = uint16_t(rem_[r] - f);
      rem_[R + c] = uint16_t(rem_[R + c] - f);
      pend[r][c] = true;
      ++steps_;
      argmax(r, c);
    }
    const bool paired = rem_[r] <= cfg_.pair_tol && rem_[R + c] <= cfg_.pair_tol;
    if (paired)
      for (int i = 0; i < R; ++i)
        for (int j = 0; j < cfg_.cols; ++j) site_[i][j] = site_[i][j] || pend[i][j];
    if (!paired && thesis_ok) site_[br][bc] = true;
  }
  // Step 3: drop the sites whose value (UQ1.15) fell below `release`.
  template <class ValueFn>
  void release(ValueFn value) {
    for (int i = 0; i < cfg_.rows; ++i)
      for (int j = 0; j < cfg_.cols; ++j)
        if (site_[i][j] && value(i, j) < cfg_.release) site_[i][j] = false;
  }
  bool site(int i, int j) const { return site_[i][j]; }
  int pair_steps() const { return steps_; }  // of the last frame

 private:
  // First (lowest index) largest rem among rows, and among columns.
  void argmax(int& r, int& c) const {
    r = 0;
    c = 0;
    for (int i = 1; i < cfg_.rows; ++i)
      if (rem_[i] > rem_[r]) r = i;
    for (int j = 1; j < cfg_.cols; ++j)
      if (rem_[cfg_.rows + j] > rem_[cfg_.rows + c]) c = j;
  }

  Config cfg_{};
  uint16_t hist_[L_MAX][K_MAX] = {};
  uint16_t rem_[K_MAX] = {};
  bool site_[R_MAX][C_MAX] = {};
  int head_ = 0, steps_ = 0;
};

}  // namespace eskin::hls
