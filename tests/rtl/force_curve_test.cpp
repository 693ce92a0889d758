// rtl/force_curve.v against hls/force_curve.h, token by token.
//
// Bound: bit-exact (cell, t, force, range, flags of every token). Inputs:
// the seed-003 scene's tokens through hls::HallBaseline, with the curves
// calibrated by the golden chain, quantised by the builder and loaded over
// the t_* port; then random deltas over the whole int16 range, so the
// search hits both ends and the extrapolated segments. The default build's
// gains and lock forces are the seed-003 scene's (GAIN_SEL 3, RES 0; 0.9,
// 4.8, 16.2 N). Random input gaps and output back-pressure.
// Timing: out_valid NB + 33 = 46 cycles after the input handshake (asserted).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "Vforce_curve.h"
#include "host/hall/hall_chain.h"
#include "hall_stream.h"
#include "hls/force_curve.h"
#include "hls/force_curve_config.h"
#include "hls/hall_baseline.h"
#include "tests/hls/hall_chain_data.h"

namespace {

using eskin::hls::ForceToken;
using eskin::hls::HallDeltaToken;
constexpr int kNb = 13;
using Kernel = eskin::hls::ForceCurve<9, kNb, 3>;

bool same(const ForceToken& a, const ForceToken& b) {
  return a.cell == b.cell && a.t == b.t && a.force_mn == b.force_mn && a.range == b.range && a.flags == b.flags;
}

HallStream<Vforce_curve, HallDeltaToken, ForceToken> stream() {
  HallStream<Vforce_curve, HallDeltaToken, ForceToken> s;
  s.drive = [](Vforce_curve& m, const HallDeltaToken& t) {
    m.in_id = t.id, m.in_t = t.t, m.in_flags = t.flags;
    m.in_dx = uint16_t(t.d[0]), m.in_dy = uint16_t(t.d[1]), m.in_dz = uint16_t(t.d[2]);
  };
  s.read = [](const Vforce_curve& m) {
    ForceToken f;
    f.cell = m.out_cell, f.t = m.out_t, f.force_mn = int32_t(m.out_force_mn), f.range = m.out_range;
    f.flags = m.out_flags;
    return f;
  };
  s.same = same;
  return s;
}

struct Bench {
  std::unique_ptr<Kernel> k;
  std::unique_ptr<ClockedDut<Vforce_curve>> d;
  std::vector<HallDeltaToken> scene;
};

Bench make_bench() {
  Bench s;
  const auto data = eskin::test::hall_tokens("hall_003_metamaterial.yaml", 3.7);
  const eskin::sim::HallWorld w(data.scene.hall);
  const auto& h = w.config();
  eskin::hls::ForceCurveConfig<kNb, 3> cfg;
  for (int a = 0; a < 3; ++a) cfg.gain[a] = eskin::hls::force_curve_gain(eskin::mlx90393::sensitivity_uT(h.mlx, a));
  // The RTL's default parameters are this scene's setting.
  EXPECT_EQ(cfg.gain[0], 1540);
  EXPECT_EQ(cfg.gain[2], 2478);
  cfg.lock_mn[0] = 900, cfg.lock_mn[1] = 4800, cfg.lock_mn[2] = 16200;
  s.k = std::make_unique<Kernel>(cfg);
  s.d = std::make_unique<ClockedDut<Vforce_curve>>();
  s.d->reset();
  const auto curves = eskin::hall::calibrate_force_curves(w, data.scene.seed);
  for (int c = 0; c < 9; ++c) {
    const auto t = eskin::hls::force_curve_table<kNb>(curves[size_t(c)].db_ut.data(), curves[size_t(c)].force_n.data(), kNb);
    s.k->table(c) = t;
    for (int i = 0; i < kNb; ++i)
      for (int which = 0; which < 3; ++which) {
        auto& m = s.d->m;
        m.t_valid = 1, m.t_cell = uint8_t(c), m.t_index = uint8_t(i), m.t_which = uint8_t(which);
        m.t_value = uint32_t(which == 0 ? t.db[i] : which == 1 ? t.f[i] : t.slope[i]);
        s.d->tick();
      }
  }
  s.d->m.t_valid = 0;
  eskin::hls::HallBaseline<9, 4> base;
  for (const auto& t : data.tokens) {
    HallDeltaToken d;
    if (base.push(t, d)) s.scene.push_back(d);
  }
  return s;
}

std::vector<ForceToken> expected(Kernel& k, const std::vector<HallDeltaToken>& in) {
  std::vector<ForceToken> out;
  for (const auto& t : in) {
    ForceToken f;
    if (k.push(t, f)) out.push_back(f);
  }
  return out;
}

TEST(ForceCurveRtl, BitExactOnSceneAndRandomDeltas) {
  Bench s = make_bench();
  std::vector<HallDeltaToken> in(s.scene.begin(), s.scene.begin() + 6000);
  std::mt19937_64 rng(4);
  for (int i = 0; i < 3000; ++i) {
    HallDeltaToken t;
    t.id = uint8_t(rng() % 11);  // 9 and 10 are not cells
    t.t = uint32_t(i);
    const int shift = int(rng() % 16);
    for (auto& v : t.d) v = int16_t(int16_t(rng()) >> shift);
    t.flags = uint8_t(rng() & 0x87);
    in.push_back(t);
  }
  const auto want = expected(*s.k, in);
  auto st = stream();
  st.run(*s.d, in, 0.7, 0.6, 5);
  ASSERT_EQ(st.outs.size(), want.size());
  int ranges[3] = {0, 0, 0};
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_TRUE(same(st.outs[i], want[i])) << "token " << i << ": rtl " << st.outs[i].force_mn << " hls "
                                           << want[i].force_mn;
    ++ranges[want[i].range];
  }
  EXPECT_GT(ranges[0], 100);
  EXPECT_GT(ranges[1], 100);
  EXPECT_GT(ranges[2], 100);
}

TEST(ForceCurveRtl, LatencyIsNbPlus33) {
  Bench s = make_bench();
  const std::vector<HallDeltaToken> in(s.scene.begin(), s.scene.begin() + 50);
  auto st = stream();
  st.run(*s.d, in, 1.0, 1.0, 6);
  ASSERT_EQ(st.out_cycles.size(), in.size());
  // The schedule in rtl/force_curve.v: 3 scale + 3 square + 24 root cycles,
  // NB - 2 breakpoint reads and their last compare, a fetch, the
  // interpolation and the range cycle: out_valid at NB + 33.
  for (size_t i = 0; i < in.size(); ++i) ASSERT_EQ(st.out_cycles[i], st.in_cycles[i] + kNb + 33) << i;
}

}  // namespace
