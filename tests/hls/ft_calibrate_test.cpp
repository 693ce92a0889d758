// hls/ft_calibrate.h against the golden W = C * dB (host/golden/ft_calibrate.h)
// on the seed-002 scene, C calibrated by the golden fit and loaded entry by
// entry as the LOAD_C command would.
#include "hls/ft_calibrate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "host/hall/hall_chain.h"
#include "hls/ft_calibrate_config.h"
#include "hls/hall_baseline.h"
#include "tests/hls/hall_chain_data.h"

namespace eskin {
namespace {

constexpr int kFrac = 16;

TEST(FtCalibrateHls, WithinEntryAndOutputRoundingOfGolden) {
  const auto data = test::hall_tokens("hall_002_magtac.yaml", 2.0);
  const sim::HallWorld w(data.scene.hall);
  const HallConfig& h = w.config();
  const hall::WrenchCalibration cal = hall::calibrate_wrench(w, data.scene.seed, 120);
  hls::FtCalibrate<kFrac> k;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j)
      k.load(i, j, hls::ft_entry(cal.c(i, j), mlx90393::sensitivity_uT(h.mlx, j % 3), kFrac, i, j));
  hls::HallBaseline<3, 4> base;
  int frames = 0;
  double worst_ratio = 0;
  int16_t db[9] = {};
  for (const auto& tok : data.tokens) {
    hls::HallDeltaToken d;
    if (!base.push(tok, d)) continue;
    for (int a = 0; a < 3; ++a) db[3 * d.id + a] = d.d[a];
    hls::WrenchToken out;
    if (!k.push(d, out)) continue;
    ++frames;
    // Golden on the same deltas: W = C (dB * sens), in mN.
    golden::Vec9 b;
    for (int j = 0; j < 9; ++j) b(j) = db[j] * mlx90393::sensitivity_uT(h.mlx, j % 3);
    const golden::Vec6 g = golden::ft_apply(cal.c, b) * 1000.0;
    // Bound: each entry is rounded to 2^-16 (error <= 2^-17 per LSB of
    // input), the sum once more to 1 (<= 0.5): sum_j |dB_j| 2^-17 + 0.5.
    double bound = 0.5;
    for (int j = 0; j < 9; ++j) bound += std::fabs(db[j]) * std::ldexp(1.0, -kFrac - 1);
    for (int i = 0; i < 6; ++i) {
      const double e = std::fabs(out.w[i] - g(i));
      ASSERT_LE(e, bound + 1e-9) << "frame " << frames << " axis " << i;
      worst_ratio = std::max(worst_ratio, e / bound);
    }
  }
  EXPECT_GT(frames, 900);
  std::printf("ft_calibrate: %d frames, worst error %.2f of its bound\n", frames, worst_ratio);
}

TEST(FtCalibrateHls, IncompleteFramesAreSkippedAndFlagsMerge) {
  hls::FtCalibrate<16, 8> k;  // sensors 8, 9, 10
  k.load(2, 2, 1 << 16);      // Fz = dB_z of sensor 8, exactly
  hls::HallDeltaToken d;
  hls::WrenchToken out;
  d.id = 8, d.d[2] = -1234, d.flags = 0x04;
  EXPECT_FALSE(k.push(d, out));
  d.id = 10, d.flags = 0;     // sensor 9 missing: frame skipped
  EXPECT_FALSE(k.push(d, out));
  EXPECT_EQ(k.skipped(), 1);
  d.id = 8, d.flags = 0x80;
  k.push(d, out);
  d.id = 9, d.flags = 0;
  k.push(d, out);
  d.id = 10, d.t = 77;
  ASSERT_TRUE(k.push(d, out));
  EXPECT_EQ(out.w[2], -1234);
  EXPECT_EQ(out.w[0], 0);
  EXPECT_EQ(out.t, 77u);
  EXPECT_EQ(out.flags, 0x80);
  // Saturation at int32: 9 products of 2^31 * 2^15 >> 16 = 9 * 2^30.
  for (int j = 0; j < 9; ++j) k.load(0, j, 0x7FFFFFFF);
  d.id = 8, d.d[0] = d.d[1] = d.d[2] = 32767;
  k.push(d, out);
  d.id = 9;
  k.push(d, out);
  d.id = 10;
  ASSERT_TRUE(k.push(d, out));
  EXPECT_EQ(out.w[0], 2147483647);
}

}  // namespace
}  // namespace eskin
