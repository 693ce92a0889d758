// hls/hall_baseline.h against the golden baseline (host/golden/hall_baseline.h)
// on the seed-003 scene's device-quantised samples, and its exact rules.
#include "hls/hall_baseline.h"

#include <gtest/gtest.h>

#include <cmath>

#include "host/golden/hall_baseline.h"
#include "tests/hls/hall_chain_data.h"

namespace eskin {
namespace {

TEST(HallBaselineHls, WithinHalfAnLsbOfGolden) {
  // Golden: exact mean (double) of the first 16 samples per sensor. HLS:
  // the same sum rounded half up to an integer: |base error| <= 0.5 LSB, so
  // every unsaturated delta is within 0.5 LSB of golden's.
  const auto data = test::hall_tokens("hall_003_metamaterial.yaml", 1.5);
  const size_t ns = data.scene.hall.config.sensors.size();
  hls::HallBaseline<9, 4> k;
  golden::HallBaseline g(ns, 16);
  size_t compared = 0;
  double worst = 0;
  for (const HallFrame& f : data.frames) {
    std::vector<Vec3> in, gd;
    for (const auto& s : f) in.push_back({double(s.lsb[0]), double(s.lsb[1]), double(s.lsb[2])});
    const bool gout = g.push(in, gd);
    for (size_t i = 0; i < ns; ++i) {
      hls::HallSampleToken tok;
      tok.id = uint8_t(i);
      tok.x = uint16_t(f[i].lsb[0]), tok.y = uint16_t(f[i].lsb[1]), tok.z = uint16_t(f[i].lsb[2]);
      hls::HallDeltaToken out;
      const bool hout = k.push(tok, out);
      ASSERT_EQ(hout, gout);
      if (!hout) continue;
      for (int a = 0; a < 3; ++a) {
        const double e = std::fabs(out.d[a] - gd[i][size_t(a)]);
        worst = std::max(worst, e);
        ASSERT_LE(e, 0.5) << "sensor " << i << " axis " << a;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 10000u);
  std::printf("hall_baseline: %zu values, worst |hls - golden| %.3f LSB (bound 0.5)\n", compared, worst);
}

TEST(HallBaselineHls, OffsetFormatsLoadedBaselinesAndDrops) {
  hls::HallBaselineConfig c;
  c.offset[0] = c.offset[1] = c.offset[2] = 0x8000;  // RES 2: zero field at 0x8000
  hls::HallBaseline<2, 1, 4> k(c);                   // ids 4, 5; capture 2 samples
  hls::HallDeltaToken out;
  hls::HallSampleToken t;
  t.id = 4, t.x = 0x8000 + 10, t.y = 0x8000 - 7, t.z = 0x8000;
  EXPECT_FALSE(k.push(t, out));
  t.x = 0x8000 + 11;
  EXPECT_FALSE(k.push(t, out));
  EXPECT_EQ(k.baseline(0, 0), 11);   // (10 + 11 + 1) >> 1: half rounds up
  EXPECT_EQ(k.baseline(0, 1), -7);
  t.x = 0xFFFF;                      // +32767 - 11
  ASSERT_TRUE(k.push(t, out));
  EXPECT_EQ(out.d[0], 32767 - 11);
  t.x = 0x0000;                      // -32768 - 11 saturates
  ASSERT_TRUE(k.push(t, out));
  EXPECT_EQ(out.d[0], -32768);
  // Loaded baselines replace capture; tokens without data, of other ids, are dropped.
  k.set(1, 0, 100), k.set(1, 1, -100), k.set(1, 2, 0);
  t.id = 5, t.x = 0x8000 + 150, t.y = 0x8000, t.z = 0x8000;
  ASSERT_TRUE(k.push(t, out));
  EXPECT_EQ(out.d[0], 50);
  EXPECT_EQ(out.d[1], 100);
  t.flags = 0x10;  // status ERROR
  EXPECT_FALSE(k.push(t, out));
  t.flags = 0x01, t.id = 9;
  EXPECT_FALSE(k.push(t, out));
  EXPECT_EQ(k.dropped(), 2);
  t.id = 5;  // saturation flag passes on
  ASSERT_TRUE(k.push(t, out));
  EXPECT_EQ(out.flags, 0x01);
}

}  // namespace
}  // namespace eskin
