// Multi-touch ghost correction by active-site tracking (thesis §5.2).
//
// Input, once per frame: normalised line amplitudes (see taxel_reconstruct.h)
// r_i = sum_j g_ij for every row and c_j = sum_i g_ij for every column.
// Output: the corrected g-matrix, zero except at the active sites.
//
// Why: k touches on distinct lines light k^2 crossings in the product
// reconstruction. A DTMF skin is fast, so touches that start at different
// times can be taken one at a time and remembered.
//
// Thesis mode (simultaneous = false), the §5.2 pseudocode:
//   1. rise of every line = amplitude now - amplitude `lookback` frames ago
//      (history starts at zero: the skin is untouched before the stream).
//   2. the row and the column with the highest rise, if both rise by more
//      than `onset`, make an active site (i, j) (nothing if it already is).
//   3. each site's value is g = sqrt(r_i c_j) from its own row and column.
//   4. a site whose value is below `release` is removed (set to zero).
//   Limits: one new site per frame, chosen by the largest rise, so touches
//   that start within the same `lookback` frames are missed or (when lines
//   are shared) paired wrongly; sites sharing a line are over-estimated,
//   since sqrt(r_i c_j) counts the other sites' share of that line.
//
// Improved mode (simultaneous = true, default):
//   2'. all rows and all columns that rise by more than `onset` are paired
//       together: the filter looks for the smallest set S of (row, col)
//       crossings of the rising lines such that non-negative values on S
//       reproduce every rising line's rise (a row's rise = sum of the rises
//       of the columns it pairs with, and vice versa) within `pair_tol`
//       (max abs error). Candidate sets are enumerated exhaustively when
//       there are at most 16 crossings, otherwise rows and columns are
//       paired one to one in order of rise (a documented approximation).
//       If no set fits, it falls back to the thesis step 2.
//   2''. several equally good sets (an ambiguous pairing):
//       a. if one of them is wholly active already, the active sites explain
//          the rise (touches still ramping up, or pressing harder) and
//          nothing is added. Why: during a ramp the rise over `lookback`
//          frames is the same few-% slice of every touch, so two touches
//          with distinct pressures look alike again after they were told
//          apart; without this rule that later, ambiguous rise added the
//          ghost diagonal (the default scene's simultaneous pair with LS
//          demixing: 4 sites through the whole hold).
//       b. else the decision waits: the rising lines become "pending",
//          each with its base = its amplitude `lookback` frames before the
//          frame it started rising (later rising lines join with their own
//          base), and every following frame step 2' is redone on the rise
//          since base of the pending lines only (other lines count as not
//          rising). Why: two touches pressed together with ramps reach
//          `onset` over `lookback` frames while their rises differ by less
//          than pair_tol, but the rise since onset keeps growing in
//          proportion to each pressure, so the sets soon differ by more
//          than pair_tol. The wait ends when one set fits alone (it is
//          committed) or when the pending lines stop rising: none rises by
//          more than `onset` over `lookback` frames any more, or none grew
//          since the previous frame (a step: nothing new will come). Then
//          the last equally good sets are all committed and ambiguous()
//          turns true, as in the limits below. While pending, the pending
//          touches are not reported (on the default scene, LS demixing, the
//          pair's larger touch is reported 0.77 ms after its start, the
//          smaller 0.94 ms: there each onset fit alone and a. did the rest;
//          b. is what resolves clean 5 ms ramps whose lines all cross
//          `onset` within a few frames, tests/golden/ghost_filter_test.cpp).
//          Noise that makes every pending line fall in one frame during a
//          ramp ends the wait early (the result is then the ambiguous split).
//   3'. all active sites' values are solved jointly: non-negative least
//       squares of the site values against ALL row and column amplitudes
//       (with a 1e-12 ridge so that rank-deficient site sets get the
//       minimum-norm split instead of an arbitrary one).
//   4'. sites below `release` are removed and the rest solved again.
//   Also staggered touches whose rises overlap in time are paired correctly,
//   simultaneous touches with distinct pressures are told apart by their
//   rise since onset, and sites that share a line get their own value.
//   Limits: rises since onset (and sums of them) must differ by more than
//   about 2 * pair_tol by the time the lines stop rising to be told apart.
//   Rule a. reads an ambiguous rise on active lines as the active touches
//   pressing harder, never as new touches. Some patterns are fundamentally
//   ambiguous because line sums only fix rows + cols - 1 degrees of
//   freedom: equal rises on two opposite corners of a rectangle (rows
//   {a, a}, cols {a, a} fit both diagonals exactly), and three touches on
//   three corners of a rectangle (any three corners with non-negative
//   values reproduce the four line sums). Then ALL equally good sets are
//   made active and ambiguous() turns true; the joint solve splits the
//   amplitude over them (minimum norm), so ghosts appear and a true site
//   whose share falls below `release` can be lost. Also missed: a new touch
//   whose line rise is masked by a simultaneous release on the same line.
//   Measured on 1500 random simultaneous 2- and 3-touch cases on 10x10
//   (tests/golden/ghost_filter_test.cpp): thesis mode misses ~62% of the
//   touches, improved mode ~0.4%, ghosts 3.9% vs 1.6% of reported sites
//   (steps: the deferral cannot help there, every ambiguous case is
//   committed one frame after onset).
#pragma once

#include <Eigen/Dense>
#include <utility>
#include <vector>

namespace eskin::golden {

struct GhostFilterConfig {
  double onset = 0.05;        // line rise (g units) over `lookback` frames that starts a site
  double release = 0.05;      // a site whose value (g) falls below this is removed
  bool simultaneous = true;   // improved mode (see above); false = thesis §5.2
  int lookback = 32;          // frames to difference over (one 32-sample window at hop 1)
  double pair_tol = 0.02;     // improved mode: max |rise mismatch| (g) a pairing may leave
};

class GhostFilter {
 public:
  // Throws eskin::ConfigError naming the field for sizes < 1, lookback < 1,
  // onset <= 0, release < 0 or pair_tol < 0.
  GhostFilter(int rows, int cols, GhostFilterConfig cfg);

  // One frame of normalised line amplitudes; updates the active-site set and
  // returns the corrected taxel g-matrix (rows x cols, zero off active sites).
  // Throws eskin::ConfigError if a vector has the wrong size.
  const Eigen::MatrixXd& update(const Eigen::VectorXd& row_g, const Eigen::VectorXd& col_g);

  const std::vector<std::pair<int, int>>& active_sites() const { return sites_; }
  const Eigen::MatrixXd& g() const { return g_; }
  // True if a pairing so far had several equally good explanations.
  bool ambiguous() const { return ambiguous_; }
  // True while an ambiguous pairing waits for more rise (improved mode).
  bool pending() const { return pending_; }
  const GhostFilterConfig& config() const { return cfg_; }

 private:
  void add_site(int r, int c);
  void add_thesis(const Eigen::VectorXd& rise);
  // Smallest crossing sets of the lines with value > onset in `rise` that
  // reproduce those values within pair_tol (empty: none fits).
  std::vector<std::vector<std::pair<int, int>>> fit_pairings(const Eigen::VectorXd& rise) const;
  bool all_active(const std::vector<std::pair<int, int>>& set) const;
  void commit(const std::vector<std::vector<std::pair<int, int>>>& fits);
  void add_paired(const Eigen::VectorXd& lines, const Eigen::VectorXd& before);
  void end_pending();
  void solve_values(const Eigen::VectorXd& lines);

  int rows_, cols_;
  GhostFilterConfig cfg_;
  std::vector<Eigen::VectorXd> history_;  // ring of the last `lookback` frames (rows then cols)
  int head_ = 0;                          // oldest entry = the frame `lookback` ago
  std::vector<std::pair<int, int>> sites_;
  Eigen::VectorXd values_;                // per site, same order as sites_
  Eigen::MatrixXd g_;
  bool ambiguous_ = false;
  Eigen::VectorXd prev_lines_;            // the previous frame's lines
  // Improved mode, a pairing decision that waits (see above).
  bool pending_ = false;
  std::vector<bool> pend_line_;           // line takes part in the pending decision
  Eigen::VectorXd pend_base_;             // its amplitude just before its rise
  std::vector<std::vector<std::pair<int, int>>> pend_fits_;  // last equally good sets
};

// Non-negative least squares min ||A x - b||, x >= 0 (Lawson-Hanson active
// set). Exposed for tests; A is small (lines x sites).
Eigen::VectorXd nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace eskin::golden
