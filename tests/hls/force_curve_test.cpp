// hls/force_curve.h against the golden force curve (host/golden/force_curve.h)
// on the seed-003 scene: curves calibrated by the golden chain, quantised by
// the builder, fed with hall_baseline's deltas.
#include "hls/force_curve.h"

#include <gtest/gtest.h>

#include <cmath>

#include "host/hall/hall_chain.h"
#include "hls/force_curve_config.h"
#include "hls/hall_baseline.h"
#include "host/golden/force_curve.h"
#include "tests/hls/hall_chain_data.h"

namespace eskin {
namespace {

constexpr int kNb = 13;

TEST(ForceCurveHls, WithinDerivedBoundOfGolden) {
  const auto data = test::hall_tokens("hall_003_metamaterial.yaml", 3.7);
  const sim::HallWorld w(data.scene.hall);
  const HallConfig& h = w.config();
  const auto curves = hall::calibrate_force_curves(w, data.scene.seed);
  ASSERT_EQ(curves.size(), 9u);
  ASSERT_EQ(curves[0].db_ut.size(), size_t(kNb));
  hls::ForceCurveConfig<kNb, 3> cfg;
  double sens[3];
  for (int a = 0; a < 3; ++a) sens[a] = mlx90393::sensitivity_uT(h.mlx, a), cfg.gain[a] = hls::force_curve_gain(sens[a]);
  const auto lock = h.cells[0].stack_lock_forces_n();
  for (int r = 0; r < 3; ++r) cfg.lock_mn[r] = int32_t(std::lround(lock[size_t(r)] * 1000));
  hls::ForceCurve<9, kNb> k(cfg);
  double max_slope = 0;  // mN per 1/64 uT
  for (int c = 0; c < 9; ++c) {
    k.table(c) = hls::force_curve_table<kNb>(curves[size_t(c)].db_ut.data(), curves[size_t(c)].force_n.data(), kNb);
    for (int i = 0; i < kNb; ++i) max_slope = std::max(max_slope, std::ldexp(std::fabs(k.table(c).slope[i]), -16));
  }
  hls::HallBaseline<9, 4> base;
  int n = 0;
  double worst_ratio = 0;
  for (const auto& tok : data.tokens) {
    hls::HallDeltaToken d;
    hls::ForceToken out;
    if (!base.push(tok, d) || !k.push(d, out)) continue;
    ++n;
    double m2 = 0, dmax = 0;
    for (int a = 0; a < 3; ++a) m2 += std::pow(d.d[a] * sens[a], 2), dmax = std::max(dmax, std::fabs(double(d.d[a])));
    const double g = 1000 * golden::force_curve_apply(curves[d.id], std::sqrt(m2));
    // Bound (mN): |dB| in 1/64 uT differs from golden by the gains' rounding
    // (<= 2^-13 uT/LSB: 2^-7 |d| units per axis), the >> 6 rounding (0.5 per
    // axis), both at most sqrt(3) times in the norm, and the root's floor (1):
    // dm <= sqrt(3) (|d|max 2^-7 + 0.5) + 1. The table's breakpoints move by
    // <= 0.5 unit and 0.5 mN, its slopes by 2^-17 mN/unit over <= 2^20 units,
    // the output rounds by 0.5 mN. Through the steepest segment:
    const double dm = std::sqrt(3.0) * (dmax * std::ldexp(1.0, -7) + 0.5) + 1;
    const double bound = max_slope * (dm + 0.5) + 0.5 + 8 + 0.5;
    const double e = std::fabs(out.force_mn - g);
    ASSERT_LE(e, bound) << "token " << n << " cell " << int(d.id) << " golden " << g;
    worst_ratio = std::max(worst_ratio, e / bound);
    // The range index follows the HLS force.
    int r = 0;
    while (r < 2 && out.force_mn > cfg.lock_mn[r]) ++r;
    EXPECT_EQ(out.range, r);
  }
  EXPECT_GT(n, 10000);
  std::printf("force_curve: %d tokens, worst error %.2f of its bound (max slope %.3f mN per 1/64 uT)\n", n,
              worst_ratio, max_slope);
}

TEST(ForceCurveHls, IsqrtIsFloorOfTheRoot) {
  for (uint64_t x : {0ull, 1ull, 2ull, 3ull, 4ull, 99ull, 100ull, (1ull << 47) + 12345, (1ull << 48) - 1}) {
    const uint64_t r = hls::isqrt48(x);
    EXPECT_LE(r * r, x);
    EXPECT_GT((r + 1) * (r + 1), x);
  }
}

}  // namespace
}  // namespace eskin
