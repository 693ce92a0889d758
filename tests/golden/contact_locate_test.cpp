// Golden seed-000 localisation: universal Kriging interpolates the scan
// exactly at its nodes and reproduces its linear drift exactly between them;
// the force-scaled nearest neighbour finds single and double contacts of a
// smooth synthetic field to within the table's resolution.
#include "host/golden/contact_locate.h"

#include <gtest/gtest.h>

#include <cmath>

namespace eskin::golden {
namespace {

// A smooth synthetic "skin": 9 sensors, each sees a Gaussian bump of the
// contact position in three components (a stand-in for the field pattern).
Eigen::VectorXd signature(double x, double y) {
  Eigen::VectorXd v(27);
  int k = 0;
  for (int sy = 0; sy < 3; ++sy)
    for (int sx = 0; sx < 3; ++sx) {
      const double dx = x - (10 + 20 * sx), dy = y - (10 + 20 * sy);
      const double g = std::exp(-(dx * dx + dy * dy) / (2 * 12.0 * 12.0));
      v(k++) = g * dx / 12, v(k++) = g * dy / 12, v(k++) = g;
    }
  return v;
}

ScanGrid grid() {
  ScanGrid g;
  g.x0 = 1, g.y0 = 1, g.pitch_mm = 2, g.nx = 30, g.ny = 30, g.force_n = 2;
  return g;
}

std::vector<Eigen::VectorXd> scan_of(const ScanGrid& g, bool linear) {
  std::vector<Eigen::VectorXd> s;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.x0 + i * g.pitch_mm, y = g.y0 + j * g.pitch_mm;
      if (linear) {
        Eigen::VectorXd v(2);
        v << 3 * x - 2 * y + 5, -x + 0.5 * y;
        s.push_back(v);
      } else {
        s.push_back(signature(x, y));
      }
    }
  return s;
}

TEST(ContactLocate, KrigingIsExactAtNodesAndOnTheDrift) {
  const ScanGrid g = grid();
  const ContactLocator loc(g, scan_of(g, true), 5, 10);
  // Subdivision 5: fine node 2 of each scan cell sits on the scan node.
  for (int j = 2; j < loc.table_ny(); j += 5)
    for (int i = 2; i < loc.table_nx(); i += 5) {
      const auto p = loc.position(i, j);
      EXPECT_NEAR(loc.entry(i, j)(0), 3 * p[0] - 2 * p[1] + 5, 1e-8);
    }
  // A linear field is in the drift: reproduced everywhere, between nodes
  // and across region borders (LU solve on values ~200: 1e-8).
  for (int j = 0; j < loc.table_ny(); j += 7)
    for (int i = 0; i < loc.table_nx(); i += 3) {
      const auto p = loc.position(i, j);
      EXPECT_NEAR(loc.entry(i, j)(0), 3 * p[0] - 2 * p[1] + 5, 1e-8);
      EXPECT_NEAR(loc.entry(i, j)(1), -p[0] + 0.5 * p[1], 1e-8);
    }
}

TEST(ContactLocate, FindsSingleAndDoubleContacts) {
  const ScanGrid g = grid();
  const ContactLocator loc(g, scan_of(g, false), 10, 10);
  // Table pitch 0.2 mm: the nearest entry is within 0.14 mm, and the cubic
  // interpolation of a 12 mm Gaussian at 2 mm spacing adds far less; bound
  // 0.3 mm. Force: the field is exactly linear in force here: 1e-3 relative.
  for (auto [x, y, f] : {std::array<double, 3>{13.3, 27.1, 2.0}, {40.7, 5.2, 3.5}, {31.0, 44.4, 0.7}}) {
    const auto c = loc.locate(f / g.force_n * signature(x, y));
    ASSERT_EQ(c.size(), 1u);
    EXPECT_NEAR(c[0].x_mm, x, 0.3);
    EXPECT_NEAR(c[0].y_mm, y, 0.3);
    EXPECT_NEAR(c[0].force_n, f, 1e-2 * f);
  }
  // Two well separated contacts superpose; found strongest first. The first
  // estimate carries the other's tail (a few percent of its field): 1 mm.
  const auto two = loc.locate(2.0 * signature(12, 14) + 1.0 * signature(48, 46), 2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_NEAR(two[0].x_mm, 12, 1.0);
  EXPECT_NEAR(two[0].y_mm, 14, 1.0);
  EXPECT_NEAR(two[1].x_mm, 48, 1.0);
  EXPECT_NEAR(two[1].y_mm, 46, 1.0);
}

}  // namespace
}  // namespace eskin::golden
