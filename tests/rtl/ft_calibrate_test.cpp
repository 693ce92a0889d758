// rtl/ft_calibrate.v against hls/ft_calibrate.h, frame by frame.
//
// Bound: bit-exact (t, the six outputs, flags of every wrench; the skip
// counter). Inputs: the seed-002 scene's tokens through hls::HallBaseline,
// with C calibrated by the golden chain and loaded over the c_* port like
// the LOAD_C command, then reloaded with extreme entries (saturation) in
// the middle of the stream; tokens of sensor 1 are dropped now and then so
// frames are skipped. Random input gaps and output back-pressure.
// Timing: out_valid rises exactly 56 cycles after the closing token's
// handshake (54 RAM reads, one pipeline stage, one output register).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "Vft_calibrate.h"
#include "host/hall/hall_chain.h"
#include "hall_stream.h"
#include "hls/ft_calibrate.h"
#include "hls/ft_calibrate_config.h"
#include "hls/hall_baseline.h"
#include "tests/hls/hall_chain_data.h"

namespace {

using eskin::hls::HallDeltaToken;
using eskin::hls::WrenchToken;

bool same(const WrenchToken& a, const WrenchToken& b) {
  for (int i = 0; i < 6; ++i)
    if (a.w[i] != b.w[i]) return false;
  return a.t == b.t && a.flags == b.flags;
}

HallStream<Vft_calibrate, HallDeltaToken, WrenchToken> stream() {
  HallStream<Vft_calibrate, HallDeltaToken, WrenchToken> s;
  s.drive = [](Vft_calibrate& m, const HallDeltaToken& t) {
    m.in_id = t.id, m.in_t = t.t, m.in_flags = t.flags;
    m.in_dx = uint16_t(t.d[0]), m.in_dy = uint16_t(t.d[1]), m.in_dz = uint16_t(t.d[2]);
  };
  s.read = [](const Vft_calibrate& m) {
    WrenchToken w;
    w.t = m.out_t, w.flags = m.out_flags;
    const uint32_t v[6] = {m.out_w0, m.out_w1, m.out_w2, m.out_w3, m.out_w4, m.out_w5};
    for (int i = 0; i < 6; ++i) w.w[i] = int32_t(v[i]);
    return w;
  };
  s.same = same;
  return s;
}

void load(ClockedDut<Vft_calibrate>& d, eskin::hls::FtCalibrate<16>& k, int i, int j, int32_t v) {
  d.m.c_valid = 1, d.m.c_row = uint8_t(i), d.m.c_col = uint8_t(j), d.m.c_value = uint32_t(v);
  d.tick();
  d.m.c_valid = 0;
  k.load(i, j, v);
}

std::vector<WrenchToken> expected(eskin::hls::FtCalibrate<16>& k, const std::vector<HallDeltaToken>& in) {
  std::vector<WrenchToken> out;
  for (const auto& t : in) {
    WrenchToken w;
    if (k.push(t, w)) out.push_back(w);
  }
  return out;
}

std::vector<HallDeltaToken> deltas(double seconds) {
  const auto data = eskin::test::hall_tokens("hall_002_magtac.yaml", seconds);
  eskin::hls::HallBaseline<3, 4> base;
  std::vector<HallDeltaToken> out;
  for (const auto& t : data.tokens) {
    HallDeltaToken d;
    if (base.push(t, d)) out.push_back(d);
  }
  return out;
}

TEST(FtCalibrateRtl, BitExactWithRuntimeCAndSkippedFrames) {
  const auto data = eskin::test::hall_tokens("hall_002_magtac.yaml", 0.01);
  const eskin::sim::HallWorld w(data.scene.hall);
  const auto cal = eskin::hall::calibrate_wrench(w, data.scene.seed, 60);
  auto d = std::make_unique<ClockedDut<Vft_calibrate>>();
  d->reset();
  eskin::hls::FtCalibrate<16> k;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j)
      load(*d, k, i, j,
           eskin::hls::ft_entry(cal.c(i, j), eskin::mlx90393::sensitivity_uT(w.config().mlx, j % 3), 16, i, j));
  auto in = deltas(1.0);
  for (size_t i = 40; i < in.size(); i += 53)
    if (in[i].id == 1) in.erase(in.begin() + long(i));  // a missing sensor-1 token
  const size_t half = in.size() / 2;
  const std::vector<HallDeltaToken> a(in.begin(), in.begin() + long(half));
  std::vector<HallDeltaToken> b(in.begin() + long(half), in.end());
  for (int16_t v : {int16_t(32767), int16_t(-32768)})  // full-scale frames
    for (uint8_t id = 0; id < 3; ++id) {
      HallDeltaToken t;
      t.id = id, t.d[0] = t.d[1] = t.d[2] = v;
      b.push_back(t);
    }
  auto s = stream();
  const auto want_a = expected(k, a);
  s.run(*d, a, 0.8, 0.6, 1);
  // Reload a row with extreme entries: saturation both ways.
  for (int j = 0; j < 9; ++j) load(*d, k, 4, j, int32_t(0x7FFFFFFF));
  auto s2 = stream();
  const auto want_b = expected(k, b);
  s2.run(*d, b, 0.9, 0.5, 2);
  ASSERT_EQ(s.outs.size(), want_a.size());
  ASSERT_EQ(s2.outs.size(), want_b.size());
  for (size_t i = 0; i < want_a.size(); ++i) ASSERT_TRUE(same(s.outs[i], want_a[i])) << "frame " << i;
  int sat = 0;
  for (size_t i = 0; i < want_b.size(); ++i) {
    ASSERT_TRUE(same(s2.outs[i], want_b[i])) << "frame " << half + i;
    sat += (want_b[i].w[4] == 2147483647) + 2 * (want_b[i].w[4] == int32_t(0x80000000));
  }
  EXPECT_EQ(sat, 3);  // one frame at each rail
  EXPECT_EQ(d->m.skipped, k.skipped());
  EXPECT_GT(k.skipped(), 5);
  EXPECT_GT(want_a.size() + want_b.size(), 400u);
}

TEST(FtCalibrateRtl, LatencyIs56Cycles) {
  const auto in = deltas(0.15);
  auto d = std::make_unique<ClockedDut<Vft_calibrate>>();
  d->reset();
  auto s = stream();
  s.run(*d, in, 1.0, 1.0, 3);
  ASSERT_FALSE(s.out_cycles.empty());
  // Frames close on sensor 2's tokens (every third input).
  size_t f = 0;
  for (size_t i = 0; i < in.size() && f < s.out_cycles.size(); ++i)
    if (in[i].id == 2 && i >= 2) {
      ASSERT_EQ(s.out_cycles[f], s.in_cycles[i] + 56) << "frame " << f;
      ++f;
    }
  EXPECT_EQ(f, s.out_cycles.size());
}

}  // namespace
