// Golden seed-003 force curve: a piecewise-linear sweep is recovered exactly,
// breakpoints land on the lock forces, and the ends extrapolate linearly.
#include "host/golden/force_curve.h"

#include <gtest/gtest.h>

namespace eskin::golden {
namespace {

// A three-range response: sensitivities 40, 12, 4 uT/N with locks at 0.9,
// 4.8, 16.2 N (the seed's ranges), sampled every 0.05 N.
double response(double f) {
  if (f <= 0.9) return 40 * f;
  if (f <= 4.8) return 36 + 12 * (f - 0.9);
  return 36 + 46.8 + 4 * (f - 4.8);
}

TEST(ForceCurve, RecoversPiecewiseLinearSweepExactly) {
  std::vector<double> db, f;
  for (int k = 0; k <= 324; ++k) f.push_back(k * 0.05), db.push_back(response(k * 0.05));
  const ForceCurve c = fit_force_curve(db, f, {0.9, 4.8, 16.2}, 2);
  ASSERT_EQ(c.force_n.size(), 7u);
  EXPECT_DOUBLE_EQ(c.force_n[2], 0.9);
  EXPECT_DOUBLE_EQ(c.force_n[4], 4.8);
  // Linear on each range and the breakpoints on the locks: the inverse is
  // exact up to rounding (1e-12 N).
  for (double force : {0.01, 0.3, 0.9, 1.7, 4.0, 4.8, 9.9, 16.2})
    EXPECT_NEAR(force_curve_apply(c, response(force)), force, 1e-12) << force;
  // Past the last breakpoint the last slope continues.
  EXPECT_NEAR(force_curve_apply(c, response(16.2) + 4), 17.2, 1e-12);
}

}  // namespace
}  // namespace eskin::golden
