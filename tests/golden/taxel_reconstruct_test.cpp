// Taxel reconstruction (thesis §3.2) and its calibrated inverse.
#include <gtest/gtest.h>

#include <cmath>

#include "eskin/skin_config.h"
#include "host/golden/taxel_reconstruct.h"

using eskin::Conductance;
using eskin::SkinConfig;
using namespace eskin::golden;

namespace {

std::vector<Conductance> all_kinds() {
  Conductance lin;
  lin.kind = Conductance::Kind::Linear;
  lin.p_max_kpa = 80.0;
  Conductance sat;
  sat.kind = Conductance::Kind::Saturating;
  sat.p_half_kpa = 40.0;
  Conductance tab;
  tab.kind = Conductance::Kind::Table;
  tab.table_p_kpa = {0.0, 10.0, 30.0, 70.0, 150.0};
  tab.table_g = {0.0, 0.2, 0.5, 0.8, 0.95};
  return {lin, sat, tab};
}

double p_top(const Conductance& c) {
  switch (c.kind) {
    case Conductance::Kind::Linear: return c.p_max_kpa;       // g saturates beyond
    case Conductance::Kind::Saturating: return 10 * c.p_half_kpa;
    case Conductance::Kind::Table: return c.table_p_kpa.back();
  }
  return 0;
}

}  // namespace

// Bound: exact equality. T_ij = r_i c_j is one double multiplication of the
// given values, so the result must be the correctly rounded product.
TEST(GoldenTaxelReconstruct, ProductIsOuterProduct) {
  Eigen::VectorXd r(3), c(2);
  r << 1.0, 0.5, 0.0;
  c << 0.25, 3.0;
  Eigen::MatrixXd t = taxel_product(r, c);
  ASSERT_EQ(t.rows(), 3);
  ASSERT_EQ(t.cols(), 2);
  EXPECT_EQ(t(0, 0), 0.25);
  EXPECT_EQ(t(0, 1), 3.0);
  EXPECT_EQ(t(1, 0), 0.125);
  EXPECT_EQ(t(1, 1), 1.5);
  EXPECT_EQ(t(2, 0), 0.0);
  EXPECT_EQ(t(2, 1), 0.0);
}

// Bound: 1e-9 kPa. A single touch g at (i, j) gives r_i = c_j = g, so
// sqrt(r_i c_j) = g up to one rounding; through the ADC-LSB scaling and back
// (multiply then divide by full_carrier_lsb) g moves by a few ulp (~1e-16).
// The steepest inverse here, saturating at p = 10 p_half, has dp/dg =
// p_half / (1-g)^2 ~ 5e3 kPa, so the pressure error is < 1e-11 kPa: 1e-9
// leaves two orders of margin. Off the touched row and column all must be 0.
TEST(GoldenTaxelReconstruct, SingleTouchRoundTripEveryConductanceKind) {
  SkinConfig skin;
  skin.rows = 4;
  skin.cols = 5;
  const double full = skin.full_carrier_lsb();
  for (const Conductance& cond : all_kinds()) {
    for (int k = 1; k <= 50; ++k) {
      const double p = p_top(cond) * k / 50.0;
      const int i = k % skin.rows, j = (3 * k) % skin.cols;
      const double g = cond.g(p);
      Eigen::VectorXd row_lsb = Eigen::VectorXd::Zero(skin.rows);
      Eigen::VectorXd col_lsb = Eigen::VectorXd::Zero(skin.cols);
      row_lsb[i] = g * full;  // what the decoder would measure, ADC LSB peak
      col_lsb[j] = g * full;
      Eigen::MatrixXd pr = taxel_pressure(row_lsb / full, col_lsb / full, cond);
      for (int a = 0; a < skin.rows; ++a)
        for (int b = 0; b < skin.cols; ++b) {
          const double want = (a == i && b == j) ? p : 0.0;
          EXPECT_NEAR(pr(a, b), want, 1e-9)
              << "kind " << int(cond.kind) << " p " << p << " at (" << a << "," << b << ")";
        }
      // The thesis product of the same single touch is g^2 at the site; g went
      // through * full / full (an ulp or two) and g <= 1, so 1e-15 holds.
      Eigen::MatrixXd t = taxel_product(row_lsb / full, col_lsb / full);
      EXPECT_NEAR(t(i, j), g * g, 1e-15);
    }
  }
}

// Bound: exact zero. Magnitudes are never negative; a negative estimate
// (e.g. from a demixer) must not make sqrt produce NaN, it means "no line".
TEST(GoldenTaxelReconstruct, NegativeLineAmplitudesGiveZeroNotNaN) {
  Eigen::VectorXd r(2), c(2);
  r << -0.1, 0.36;
  c << 0.25, -1e-12;
  Eigen::MatrixXd g = taxel_g(r, c);
  EXPECT_EQ(g(0, 0), 0.0);
  EXPECT_EQ(g(0, 1), 0.0);
  EXPECT_EQ(g(1, 1), 0.0);
  EXPECT_NEAR(g(1, 0), 0.3, 1e-15);  // sqrt(0.36 * 0.25)
  EXPECT_TRUE(g.allFinite());
}
