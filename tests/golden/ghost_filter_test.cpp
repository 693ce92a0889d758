// Multi-touch ghost correction (thesis §5.2) in thesis and improved modes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "eskin/skin_config.h"
#include "host/golden/ghost_filter.h"
#include "host/golden/taxel_reconstruct.h"

using namespace eskin::golden;
using Site = std::pair<int, int>;

namespace {

struct Touch {
  int r, c;
  double g;            // conductance fraction once fully pressed
  double t_on_ms;      // press starts
  double ramp_ms = 0;  // 0: step; else linear rise over ramp_ms
  double t_off_ms = 1e30;
  double at(double t) const {
    if (t < t_on_ms || t >= t_off_ms) return 0.0;
    if (ramp_ms <= 0) return g;
    return g * std::min(1.0, (t - t_on_ms) / ramp_ms);
  }
};

// Ground-truth g-matrix at time t, and the noise-free normalised line
// amplitudes a DTMF skin would give for it (row and column sums).
Eigen::MatrixXd truth_at(const std::vector<Touch>& ts, int rows, int cols, double t) {
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(rows, cols);
  for (const Touch& k : ts) g(k.r, k.c) += k.at(t);
  return g;
}

std::set<Site> sites_of(const GhostFilter& f) {
  return {f.active_sites().begin(), f.active_sites().end()};
}

std::set<Site> support(const Eigen::MatrixXd& g) {
  std::set<Site> s;
  for (int i = 0; i < g.rows(); ++i)
    for (int j = 0; j < g.cols(); ++j)
      if (g(i, j) > 0) s.insert({i, j});
  return s;
}

// The thesis scenario (§5.2, Fig. 5.4/5.5): 10x10 skin, three touches on
// distinct rows and columns, starting 10 ms apart and then held.
std::vector<Touch> thesis_touches(double ramp_ms) {
  return {{1, 2, 0.60, 5.0, ramp_ms}, {4, 7, 0.35, 15.0, ramp_ms}, {8, 5, 0.50, 25.0, ramp_ms}};
}

// Runs the filter over frames every `frame_ms` until `t_end_ms` and checks
// after every frame that no ghost is ever active (every site is a started
// touch). Returns the last frame time.
double run_and_check_no_ghost(GhostFilter& f, const std::vector<Touch>& ts, double frame_ms,
                              double t_end_ms) {
  const int R = 10, C = 10;
  double t = 0;
  for (long n = 0; (t = n * frame_ms) <= t_end_ms; ++n) {
    Eigen::MatrixXd g = truth_at(ts, R, C, t);
    f.update(g.rowwise().sum(), g.colwise().sum().transpose());
    for (const Site& s : f.active_sites())
      EXPECT_GT(g(s.first, s.second), 0.0) << "ghost at (" << s.first << "," << s.second
                                           << ") t=" << t << " ms";
  }
  return t;
}

}  // namespace

// Product reconstruction: 3 touches on 3 distinct rows and 3 distinct columns
// make all 3 x 3 crossings non-zero (smallest product is 0.35^2 = 0.1225 and
// every other taxel is exactly 0), so exactly 9 taxels exceed any threshold
// in (0, 0.1225): we use onset^2 = 0.0025.
// Ghost filter: the touches start 10 ms apart (>> one 32-frame window at 35
// kHz, and >> 1 frame at 1 kHz with lookback 1), so each rise is seen alone
// and pairs its own row and column; each site then owns its row and column,
// so both modes' values equal g up to a sqrt/solve rounding: 1e-9 is far
// above that (~1e-15) and far below any ghost (>= 0.35).
TEST(GoldenGhostFilter, ThesisThreeStaggeredTouchesExactlyThreeSites) {
  const int R = 10, C = 10;
  struct Run {
    double frame_ms, ramp_ms;
    int lookback;
  };
  // Frames every ADC sample (35 kHz) with a 1 ms press ramp (like a 32-sample
  // window filling) and lookback 32; and frames every ms with steps.
  for (Run run : {Run{1.0 / 35.0, 1.0, 32}, Run{1.0, 0.0, 1}}) {
    for (bool improved : {false, true}) {
      SCOPED_TRACE((improved ? "improved, frame " : "thesis, frame ") +
                   std::to_string(run.frame_ms) + " ms");
      auto ts = thesis_touches(run.ramp_ms);
      GhostFilterConfig cfg;
      cfg.simultaneous = improved;
      cfg.lookback = run.lookback;
      GhostFilter f(R, C, cfg);
      double t = run_and_check_no_ghost(f, ts, run.frame_ms, 40.0);
      Eigen::MatrixXd truth = truth_at(ts, R, C, t);
      Eigen::VectorXd rows = truth.rowwise().sum(), cols = truth.colwise().sum().transpose();

      Eigen::MatrixXd prod = taxel_product(rows, cols);
      EXPECT_EQ((prod.array() > cfg.onset * cfg.onset).count(), 9);

      EXPECT_EQ(sites_of(f), support(truth));
      EXPECT_LT((f.g() - truth).cwiseAbs().maxCoeff(), 1e-9);
    }
  }
}

// Release: once a touch lifts, its line amplitudes drop to 0, so its site
// value (0) is below release and the site must go; the others stay exact
// (bound 1e-9 as above).
TEST(GoldenGhostFilter, LiftedTouchIsReleased) {
  for (bool improved : {false, true}) {
    auto ts = thesis_touches(0.0);
    ts[1].t_off_ms = 32.0;
    GhostFilterConfig cfg;
    cfg.simultaneous = improved;
    cfg.lookback = 1;
    GhostFilter f(10, 10, cfg);
    double t = run_and_check_no_ghost(f, ts, 1.0, 40.0);
    Eigen::MatrixXd truth = truth_at(ts, 10, 10, t);
    EXPECT_EQ(sites_of(f), (std::set<Site>{{1, 2}, {8, 5}}));
    EXPECT_LT((f.g() - truth).cwiseAbs().maxCoeff(), 1e-9);
  }
}

// A second touch on an already active row, 5 frames after the first (both
// rises inside one 32-frame lookback). Improved mode pairs row 2's rise
// (0.8) with columns 3 and 6 (0.5 + 0.3, exact) and the joint solve gives
// each its own value: bound 1e-9 (exact data, full-rank 2-site system).
// Thesis mode uses sqrt(r_2 c_6) = sqrt(0.8 * 0.3) = 0.49 for a 0.3 touch:
// the documented over-estimate on shared lines (asserted > 0.1 off).
TEST(GoldenGhostFilter, SharedRowImprovedExactThesisOverestimates) {
  std::vector<Touch> ts = {{2, 3, 0.5, 0.0}, {2, 6, 0.3, 5.0 / 35.0}};
  for (bool improved : {false, true}) {
    GhostFilterConfig cfg;
    cfg.simultaneous = improved;
    GhostFilter f(10, 10, cfg);
    double t = run_and_check_no_ghost(f, ts, 1.0 / 35.0, 3.0);
    Eigen::MatrixXd truth = truth_at(ts, 10, 10, t);
    EXPECT_EQ(sites_of(f), support(truth));
    if (improved)
      EXPECT_LT((f.g() - truth).cwiseAbs().maxCoeff(), 1e-9);
    else
      EXPECT_GT(f.g()(2, 6) - 0.3, 0.1);
  }
}

// Truly simultaneous touches (all start in the same frame, steps). Thesis
// mode adds one site per frame from the largest rises, so it can find only
// one of them (and may pair lines of different touches when lines are
// shared); improved mode pairs all rising lines at once.
// Asserted: (1) improved mode's ghost and miss rates are <= thesis mode's;
// (2) in every case whose pairing is provably unambiguous -- all touches on
// distinct rows and columns and all g pairwise more than 2 * pair_tol apart,
// so any other pairing leaves a row/column mismatch >= |g_a - g_b| / 2 >
// pair_tol -- improved mode finds exactly the true sites with values within
// 1e-9 (exact data, full-rank system).
TEST(GoldenGhostFilter, SimultaneousTouchesGhostRates) {
  const int R = 10, C = 10, cases = 1500;
  std::mt19937 rng(20231122);
  std::uniform_int_distribution<int> pos(0, 9);
  std::uniform_real_distribution<double> gdist(0.1, 0.9);
  struct Tally {
    long ghosts = 0, misses = 0, reported = 0, exact = 0;
  } tally[2];
  long truth_sites = 0, unambiguous = 0, unambiguous_exact = 0, product_ghosts = 0;
  for (int n = 0; n < cases; ++n) {
    const int k = 2 + n % 2;
    std::vector<Touch> ts;
    std::set<Site> used;
    while (int(ts.size()) < k) {
      Touch t{pos(rng), pos(rng), gdist(rng), 0.0};
      bool distinct_g = true;
      for (const Touch& o : ts) distinct_g &= std::fabs(o.g - t.g) > 0.05;
      if (distinct_g && used.insert({t.r, t.c}).second) ts.push_back(t);
    }
    std::set<int> rows_used, cols_used;
    for (const Touch& t : ts) rows_used.insert(t.r), cols_used.insert(t.c);
    const bool distinct_lines = int(rows_used.size()) == k && int(cols_used.size()) == k;
    Eigen::MatrixXd truth = truth_at(ts, R, C, 0.0);
    const std::set<Site> want = support(truth);
    truth_sites += k;
    Eigen::MatrixXd prod = taxel_product(truth.rowwise().sum(), truth.colwise().sum().transpose());
    product_ghosts += (prod.array() > 0).count() - k;

    for (int mode = 0; mode < 2; ++mode) {
      GhostFilterConfig cfg;
      cfg.simultaneous = mode == 1;
      cfg.lookback = 4;
      GhostFilter f(R, C, cfg);
      for (int frame = 0; frame < 8; ++frame)  // longer than the rise stays visible
        f.update(truth.rowwise().sum(), truth.colwise().sum().transpose());
      std::set<Site> got = sites_of(f);
      for (const Site& s : got) tally[mode].ghosts += !want.count(s);
      for (const Site& s : want) tally[mode].misses += !got.count(s);
      tally[mode].reported += long(got.size());
      const bool exact = got == want && (f.g() - truth).cwiseAbs().maxCoeff() < 1e-9;
      tally[mode].exact += exact;
      if (mode == 1 && distinct_lines) {
        ++unambiguous;
        unambiguous_exact += exact;
        EXPECT_TRUE(exact) << "case " << n;
      }
    }
  }
  for (int mode = 0; mode < 2; ++mode)
    std::printf("[ghost rates] %-8s: ghosts %ld of %ld reported sites (%.2f%%), missed %ld of %ld "
                "touches (%.2f%%), exact cases %ld of %d\n",
                mode ? "improved" : "thesis", tally[mode].ghosts, tally[mode].reported,
                100.0 * tally[mode].ghosts / std::max(1L, tally[mode].reported),
                tally[mode].misses, truth_sites, 100.0 * tally[mode].misses / truth_sites,
                tally[mode].exact, cases);
  std::printf("[ghost rates] product reconstruction: %ld ghost taxels over %d cases; "
              "unambiguous cases exact in improved mode: %ld of %ld\n",
              product_ghosts, cases, unambiguous_exact, unambiguous);
  const double ghost_rate[2] = {double(tally[0].ghosts) / std::max(1L, tally[0].reported),
                                double(tally[1].ghosts) / std::max(1L, tally[1].reported)};
  EXPECT_LE(ghost_rate[1], ghost_rate[0]);
  EXPECT_LE(tally[1].misses, tally[0].misses);
  EXPECT_GT(unambiguous, cases / 4);  // the exactness claim was exercised
}

// Equal pressures on the corners of a rectangle: rows {g, g}, cols {g, g}
// fit both diagonals exactly, so no decoder can tell them apart. The filter
// must say so, lose no touch, and report the minimum-norm split g/2 on all
// four corners (that split reproduces every line exactly: 2 * g/2 = g; the
// 1e-12 ridge biases it by ~1e-12, bound 1e-9).
TEST(GoldenGhostFilter, EqualRectangleIsAmbiguous) {
  GhostFilter f(4, 4, GhostFilterConfig{});
  Eigen::MatrixXd truth = Eigen::MatrixXd::Zero(4, 4);
  truth(0, 1) = truth(2, 3) = 0.4;
  for (int frame = 0; frame < 3; ++frame)
    f.update(truth.rowwise().sum(), truth.colwise().sum().transpose());
  EXPECT_TRUE(f.ambiguous());
  EXPECT_EQ(sites_of(f), (std::set<Site>{{0, 1}, {0, 3}, {2, 1}, {2, 3}}));
  for (const Site& s : f.active_sites()) EXPECT_NEAR(f.g()(s.first, s.second), 0.2, 1e-9);
}

// Two truly simultaneous touches with distinct pressures and 5 ms linear
// ramps (the default scene's last phase), frames every sample at 35 kHz,
// lookback 32. Over a 32-frame lookback the two ramps rise by g * 32/175,
// so when the lines of the second touch cross `onset` both diagonals of the
// rectangle fit the rises within pair_tol (0.5 vs 0.375: 0.375 crosses
// 0.05 at frame 24, the wrong diagonal leaves |0.0686 - 0.0514| / 2 = 0.009
// < 0.02; 0.6 vs 0.5 at frame 18: 0.005; 0.55 vs 0.45 at frame 20: 0.006;
// all computed from g * n / 175 at the frame n where the smaller touch's
// rise first exceeds onset, its first fitting frame). The filter must
// wait (pending() seen true) and decide on the rise since onset, which
// tells the diagonals apart (|g_a - g_b| * ramp fraction / 2 > pair_tol
// long before the ramps end); and later in the ramps, when the 32-frame
// rises are ambiguous again, keep the active diagonal (ghost_filter.h 2''a).
// Checked: (1) no ghost in any frame (every active site is a touch that has
// started); (2) from the end of the ramps on, exactly the 2 true sites and
// not ambiguous; (3) values: noise-free, each site owns its row and its
// column, so the joint solve is exact up to the 1e-12 ridge bias and
// rounding: bound 1e-9. With uniform noise of +-eps = 0.002 g added to every
// line in every frame: a site alone on its row r and column c gets
// (r + c) / 2, so its error is <= eps (+ the 1e-9 above); noise alone rises
// by <= 2 eps = 0.004 < onset, so it starts nothing, and the true diagonal
// always fits (its mismatch is <= 2 eps < pair_tol), so only the true
// diagonal can ever be the unique fit.
TEST(GoldenGhostFilter, SimultaneousRampsDistinctPressuresResolved) {
  struct Case {
    int rows, cols;
    std::vector<Touch> ts;
  };
  const double ramp_ms = 5.0, t_on = 1.0, frame_ms = 1.0 / 35.0, t_end = 12.0;
  const std::vector<Case> cases = {
      {3, 3, {{1, 0, 0.5, t_on, ramp_ms}, {0, 2, 0.375, t_on, ramp_ms}}},
      {10, 10, {{2, 5, 0.6, t_on, ramp_ms}, {7, 1, 0.5, t_on, ramp_ms}}},
      {10, 10, {{4, 4, 0.45, t_on, ramp_ms}, {6, 8, 0.55, t_on, ramp_ms}}}};
  for (size_t n = 0; n < cases.size(); ++n) {
    for (double eps : {0.0, 0.002}) {
      SCOPED_TRACE("case " + std::to_string(n) + ", noise " + std::to_string(eps));
      const Case& k = cases[n];
      std::mt19937 rng(unsigned(11 + n));
      std::uniform_real_distribution<double> noise(-eps, eps);
      GhostFilterConfig cfg;
      cfg.lookback = 32;
      GhostFilter f(k.rows, k.cols, cfg);
      bool waited = false;
      long checked = 0;
      for (long i = 0; i * frame_ms <= t_end; ++i) {
        const double t = i * frame_ms;
        Eigen::MatrixXd g = truth_at(k.ts, k.rows, k.cols, t);
        Eigen::VectorXd rows = g.rowwise().sum(), cols = g.colwise().sum().transpose();
        for (Eigen::Index j = 0; j < rows.size(); ++j) rows[j] += noise(rng);
        for (Eigen::Index j = 0; j < cols.size(); ++j) cols[j] += noise(rng);
        f.update(rows, cols);
        waited |= f.pending();
        for (const Site& s : f.active_sites())
          ASSERT_GT(g(s.first, s.second), 0.0) << "ghost at (" << s.first << "," << s.second
                                               << ") t=" << t << " ms";
        if (t < t_on + ramp_ms) continue;
        ++checked;
        ASSERT_EQ(sites_of(f), support(g)) << "t=" << t << " ms";
        EXPECT_LT((f.g() - g).cwiseAbs().maxCoeff(), eps + 1e-9) << "t=" << t << " ms";
      }
      EXPECT_TRUE(waited);  // the onset pairing was ambiguous: the deferral was exercised
      EXPECT_FALSE(f.ambiguous());
      EXPECT_GT(checked, 100);
    }
  }
}

// NNLS against brute force: the optimum of min ||Ax - b||, x >= 0 is the
// unconstrained least-squares solution on some support that is feasible;
// enumerating all supports of a 4-column problem and keeping the best
// feasible one gives the reference. Both solve well-conditioned random
// systems, so they agree to rounding: bound 1e-9.
TEST(GoldenGhostFilter, NnlsMatchesBruteForce) {
  std::mt19937 rng(7);
  std::normal_distribution<double> nd(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::MatrixXd A(6, 4);
    Eigen::VectorXd b(6);
    for (int i = 0; i < 6; ++i) {
      b[i] = nd(rng);
      for (int j = 0; j < 4; ++j) A(i, j) = nd(rng);
    }
    double best = b.squaredNorm();
    Eigen::VectorXd xbest = Eigen::VectorXd::Zero(4);
    for (int mask = 1; mask < 16; ++mask) {
      std::vector<int> cols;
      for (int j = 0; j < 4; ++j)
        if (mask >> j & 1) cols.push_back(j);
      Eigen::MatrixXd As(6, Eigen::Index(cols.size()));
      for (size_t k = 0; k < cols.size(); ++k) As.col(Eigen::Index(k)) = A.col(cols[k]);
      Eigen::VectorXd z = As.colPivHouseholderQr().solve(b);
      if ((z.array() < 0).any()) continue;
      Eigen::VectorXd x = Eigen::VectorXd::Zero(4);
      for (size_t k = 0; k < cols.size(); ++k) x[cols[k]] = z[Eigen::Index(k)];
      double r = (A * x - b).squaredNorm();
      if (r < best) best = r, xbest = x;
    }
    Eigen::VectorXd x = nnls(A, b);
    EXPECT_TRUE((x.array() >= 0).all());
    EXPECT_LT((x - xbest).cwiseAbs().maxCoeff(), 1e-9) << "trial " << trial;
  }
}

// Bad sizes and settings name the field.
TEST(GoldenGhostFilter, ConfigErrorsNameTheField) {
  GhostFilterConfig bad;
  bad.lookback = 0;
  try {
    GhostFilter f(3, 3, bad);
    FAIL() << "lookback 0 accepted";
  } catch (const eskin::ConfigError& e) {
    EXPECT_EQ(e.field(), "ghost_filter.lookback");
  }
  bad = GhostFilterConfig{};
  bad.onset = 0.0;
  EXPECT_THROW(GhostFilter(3, 3, bad), eskin::ConfigError);
  GhostFilter f(3, 3, GhostFilterConfig{});
  try {
    f.update(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(3));
    FAIL() << "2 row amplitudes accepted for 3 rows";
  } catch (const eskin::ConfigError& e) {
    EXPECT_EQ(e.field(), "ghost_filter.row_g");
  }
}
