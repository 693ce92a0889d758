// Golden Hall baseline: the captured mean and the subtraction are exact
// (integer-valued fields in double: no rounding), frames flagged during
// capture count like any other.
#include "host/golden/hall_baseline.h"

#include <gtest/gtest.h>

namespace eskin::golden {
namespace {

TEST(HallBaseline, CapturesMeanThenSubtracts) {
  HallBaseline b(2, 4);
  std::vector<Vec3> d;
  for (int k = 0; k < 4; ++k) {
    EXPECT_TRUE(b.capturing());
    EXPECT_FALSE(b.push({{double(k), 10, -20}, {100, 2.0 * k, 8}}, d));
  }
  EXPECT_FALSE(b.capturing());
  EXPECT_EQ(b.baseline()[0][0], 1.5);  // (0+1+2+3)/4
  EXPECT_EQ(b.baseline()[1][1], 3.0);
  ASSERT_TRUE(b.push({{5, 10, -19}, {99, 3, 8}}, d));
  EXPECT_EQ(d[0][0], 3.5);
  EXPECT_EQ(d[0][1], 0.0);
  EXPECT_EQ(d[0][2], 1.0);
  EXPECT_EQ(d[1][0], -1.0);
}

TEST(HallBaseline, FrameInMicroteslaUsesEachAxisSensitivity) {
  mlx90393::Config c;
  c.gain_sel = 7;
  c.res_z = 1;
  HallFrame f(1);
  f[0].lsb = {100, -100, 100};
  const auto ut = frame_ut(f, c);
  EXPECT_DOUBLE_EQ(ut[0][0], 100 * 0.150);       // datasheet XY, GAIN_SEL 7, RES 0
  EXPECT_DOUBLE_EQ(ut[0][1], -100 * 0.150);
  EXPECT_DOUBLE_EQ(ut[0][2], 100 * 0.242 * 2);   // Z, RES 1 doubles the LSB
}

}  // namespace
}  // namespace eskin::golden
