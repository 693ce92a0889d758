// hls/hall_decouple.h against the golden decoupling (host/golden/hall_decouple.h)
// on the seed-001 scene with the golden-fitted compensation, and its guards.
#include "hls/hall_decouple.h"

#include <gtest/gtest.h>

#include <cmath>

#include "host/hall/hall_chain.h"
#include "hls/hall_baseline.h"
#include "host/golden/hall_decouple.h"
#include "tests/hls/hall_chain_data.h"

namespace eskin {
namespace {

constexpr double kQ24 = 16777216.0;

hls::HallDecoupleConfig config(const HallConfig& h, const DecoupleParams& p) {
  hls::HallDecoupleConfig c;
  for (int a = 0; a < 3; ++a) c.gain[a] = uint32_t(std::lround(mlx90393::sensitivity_uT(h.mlx, a) * 65536));
  c.k1 = int16_t(std::lround(p.k1 * 16384)), c.k2 = int16_t(std::lround(p.k2 * 16384));
  c.c1 = int32_t(std::lround(p.c1_ut * 64)), c.c2 = int32_t(std::lround(p.c2_ut * 64));
  return c;
}

TEST(HallDecoupleHls, WithinDerivedBoundOfGolden) {
  const auto data = test::hall_tokens("hall_001_split.yaml", 3.7);
  const sim::HallWorld w(data.scene.hall);
  const HallConfig& h = w.config();
  const hall::DecoupleCalibration cal = hall::calibrate_decouple(w, data.scene.seed);
  // The golden uses the compensation exactly as the FPGA holds it.
  DecoupleParams p = cal.params;
  const hls::HallDecoupleConfig cfg = config(h, p);
  p.k1 = cfg.k1 / 16384.0, p.k2 = cfg.k2 / 16384.0, p.c1_ut = cfg.c1 / 64.0, p.c2_ut = cfg.c2 / 64.0;
  hls::HallBaseline<1, 4> base;
  for (int a = 0; a < 3; ++a)  // the geomagnetic field, recorded before the film was placed
    base.set(0, a, int16_t(std::lround(h.geomagnetic_ut[size_t(a)] / mlx90393::sensitivity_uT(h.mlx, a))));
  hls::HallDecouple<0> k(cfg);
  int n = 0;
  double worst[3] = {0, 0, 0};
  for (const auto& tok : data.tokens) {
    hls::HallDeltaToken d;
    hls::DecoupleToken out;
    if (!base.push(tok, d) || !k.push(d, out)) continue;
    Vec3 b;
    double q[3];  // the field the FPGA sees, uT (its gains are rounded to 2^-16)
    for (int a = 0; a < 3; ++a) q[a] = d.d[a] * (cfg.gain[a] / 65536.0), b[size_t(a)] = q[a];
    const golden::Decoupled g = golden::hall_decouple(b, p);
    ASSERT_EQ(out.valid, g.valid);
    if (!g.valid) continue;
    ++n;
    // Bound: B is rounded to 1/128 uT per axis (and z1, z2 to 1/64 uT after
    // the Q2.14 product): the first-order change of each parameter under
    // those input errors (golden partial derivatives, by central
    // differences) plus CORDIC's residual angle atan(2^-23) and its angle
    // table's rounding (24 * 0.5 LSB), and the logarithm's truncated
    // squarings (24 fraction bits: 2 * 2^-23 * ln 2 per ln, three of them).
    const double db = 1.0 / 128 + 1.0 / 64, h_ = 1e-3;
    double bound[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) {
      Vec3 u = b, v = b;
      u[size_t(a)] += h_, v[size_t(a)] -= h_;
      const golden::Decoupled gu = golden::hall_decouple(u, p), gv = golden::hall_decouple(v, p);
      bound[0] += std::fabs(gu.rx - gv.rx) / (2 * h_) * db;
      bound[1] += std::fabs(gu.ry - gv.ry) / (2 * h_) * db;
      bound[2] += std::fabs(gu.sz - gv.sz) / (2 * h_) * db;
    }
    const double ang = std::atan(std::ldexp(1.0, -23)) + 12 / kQ24 + 1 / kQ24;
    const double lnb = 3 * 2 * std::ldexp(1.0, -23) * std::log(2.0) + 3 / kQ24;
    const double e[3] = {std::fabs(out.rx / kQ24 - g.rx), std::fabs(out.ry / kQ24 - g.ry), std::fabs(out.sz / kQ24 - g.sz)};
    const double lim[3] = {bound[0] + ang, bound[1] + ang, bound[2] + lnb};
    for (int i = 0; i < 3; ++i) {
      ASSERT_LE(e[i], lim[i]) << "token " << n << " parameter " << i;
      worst[i] = std::max(worst[i], e[i] / lim[i]);
    }
  }
  EXPECT_GT(n, 1500);
  std::printf("hall_decouple: %d tokens; worst error / bound: Rx %.2f Ry %.2f Sz %.2f\n", n, worst[0], worst[1], worst[2]);
}

TEST(HallDecoupleHls, GuardsOutOfRangeWithoutDividing) {
  hls::HallDecoupleConfig c;
  c.gain[0] = c.gain[1] = c.gain[2] = 1 << 16;  // 1 uT per LSB
  hls::HallDecouple<0> k(c);
  hls::HallDeltaToken d;
  hls::DecoupleToken out;
  d.d[0] = 10, d.d[1] = 10, d.d[2] = 0;  // z1 = 0
  ASSERT_TRUE(k.push(d, out));
  EXPECT_FALSE(out.valid);
  d.d[2] = -500;                          // z1 < 0
  k.push(d, out);
  EXPECT_FALSE(out.valid);
  d.d[0] = 900, d.d[1] = 0, d.d[2] = 500;  // Bx^2 > z1^2 + By^2
  k.push(d, out);
  EXPECT_FALSE(out.valid);
  EXPECT_EQ(out.rx, 0);
  d.d[0] = 0, d.d[1] = 300, d.d[2] = 400;  // Bx = 0: Ry = 2 atan(By/Bz) exactly in theory
  k.push(d, out);
  ASSERT_TRUE(out.valid);
  EXPECT_NEAR(out.ry / kQ24, 2 * std::atan(0.75), 1e-6);
  EXPECT_NEAR(out.sz / kQ24, std::log((400.0 * 400 + 300.0 * 300) / 800), 1e-6);
  hls::HallDeltaToken other = d;
  other.id = 1;
  EXPECT_FALSE(k.push(other, out));  // another sensor's token: no output
}

TEST(HallDecoupleHls, LogarithmAndCordicPrimitives) {
  for (uint64_t r : {1ull, 2ull, 3ull, 1000ull, 123456789ull, (1ull << 61) + 7})
    // 24 fraction bits of log2 (truncated squarings: < 2 * 2^-24 each way)
    // times ln 2, plus the final rounding: well under 2e-6.
    EXPECT_NEAR(hls::ln_q24(r) / kQ24, std::log(double(r)), 2e-6) << r;
  for (double ang : {-1.2, -0.3, 0.0, 0.01, 0.7, 1.5}) {
    int64_t x = std::llround(1e6 * std::cos(ang));
    const int32_t z = hls::cordic_vector(x, std::llround(1e6 * std::sin(ang)));
    EXPECT_NEAR(z / kQ24, ang, 1e-5) << ang;
    // Each of the 24 steps floors two shifted terms (< 1 LSB each, grown by
    // at most K afterwards): |error| < 24 * 2 * K / K = 48 LSB of 1e6.
    EXPECT_NEAR(double(x) / 1.6467602581210619, 1e6, 48.0);
  }
}

}  // namespace
}  // namespace eskin
