// rtl/hall_decouple.v against hls/hall_decouple.h, token by token.
//
// Bound: bit-exact (t, Rx, Ry, Sz, valid, flags). Inputs: the seed-001
// scene's tokens through hls::HallBaseline (geomagnetic baseline loaded as
// the SET_BASELINE command would), with the golden-fitted compensation on
// the cfg_* ports; then random deltas over the int16 range, which hit the
// guards (Bz' or a denominator <= 0), large vectors (prescaling) and the
// zero-vector case. The default build's gains are the scene's (GAIN_SEL 7,
// RES 0). Random input gaps and output back-pressure.
// Timing (asserted per token with the stream always ready): 158 + s1 + s2
// + s3 cycles for a valid token, s the prescale halvings the HLS reports;
// 11 for a guarded token; 170 + s1 + s2 for the zero vector.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "Vhall_decouple.h"
#include "host/hall/hall_chain.h"
#include "hall_stream.h"
#include "hls/hall_baseline.h"
#include "hls/hall_decouple.h"
#include "tests/hls/hall_chain_data.h"

namespace {

using eskin::hls::DecoupleToken;
using eskin::hls::HallDeltaToken;

bool same(const DecoupleToken& a, const DecoupleToken& b) {
  return a.t == b.t && a.rx == b.rx && a.ry == b.ry && a.sz == b.sz && a.valid == b.valid && a.flags == b.flags;
}

HallStream<Vhall_decouple, HallDeltaToken, DecoupleToken> stream() {
  HallStream<Vhall_decouple, HallDeltaToken, DecoupleToken> s;
  s.drive = [](Vhall_decouple& m, const HallDeltaToken& t) {
    m.in_id = t.id, m.in_t = t.t, m.in_flags = t.flags;
    m.in_dx = uint16_t(t.d[0]), m.in_dy = uint16_t(t.d[1]), m.in_dz = uint16_t(t.d[2]);
  };
  s.read = [](const Vhall_decouple& m) {
    DecoupleToken o;
    o.t = m.out_t, o.rx = int32_t(m.out_rx), o.ry = int32_t(m.out_ry), o.sz = int32_t(m.out_sz);
    o.valid = m.out_ok, o.flags = m.out_flags;
    return o;
  };
  s.same = same;
  return s;
}

struct Bench {
  eskin::hls::HallDecoupleConfig cfg;
  std::vector<HallDeltaToken> scene;
};

Bench make_bench() {
  Bench b;
  const auto data = eskin::test::hall_tokens("hall_001_split.yaml", 3.7);
  const eskin::sim::HallWorld w(data.scene.hall);
  const auto& h = w.config();
  const auto cal = eskin::hall::calibrate_decouple(w, data.scene.seed);
  for (int a = 0; a < 3; ++a)
    b.cfg.gain[a] = uint32_t(std::lround(eskin::mlx90393::sensitivity_uT(h.mlx, a) * 65536));
  EXPECT_EQ(b.cfg.gain[0], 9830u);  // the RTL defaults are this setting
  EXPECT_EQ(b.cfg.gain[2], 15860u);
  b.cfg.k1 = int16_t(std::lround(cal.params.k1 * 16384)), b.cfg.k2 = int16_t(std::lround(cal.params.k2 * 16384));
  b.cfg.c1 = int32_t(std::lround(cal.params.c1_ut * 64)), b.cfg.c2 = int32_t(std::lround(cal.params.c2_ut * 64));
  eskin::hls::HallBaseline<1, 4> base;
  for (int a = 0; a < 3; ++a)
    base.set(0, a, int16_t(std::lround(h.geomagnetic_ut[size_t(a)] / eskin::mlx90393::sensitivity_uT(h.mlx, a))));
  for (const auto& t : data.tokens) {
    HallDeltaToken d;
    if (base.push(t, d)) b.scene.push_back(d);
  }
  return b;
}

std::unique_ptr<ClockedDut<Vhall_decouple>> dut(const eskin::hls::HallDecoupleConfig& c) {
  auto d = std::make_unique<ClockedDut<Vhall_decouple>>();
  d->m.cfg_k1 = uint16_t(c.k1), d->m.cfg_k2 = uint16_t(c.k2);
  d->m.cfg_c1 = uint32_t(c.c1), d->m.cfg_c2 = uint32_t(c.c2);
  d->reset();
  return d;
}

TEST(HallDecoupleRtl, BitExactOnSceneAndRandomDeltas) {
  Bench b = make_bench();
  std::vector<HallDeltaToken> in(b.scene.begin(), b.scene.begin() + 600);
  std::mt19937_64 rng(11);
  for (int i = 0; i < 600; ++i) {
    HallDeltaToken t;
    t.id = uint8_t(rng() % 9 == 0 ? 3 : 0);
    t.t = uint32_t(i);
    const int shift = int(rng() % 15);
    for (auto& v : t.d) v = int16_t(int16_t(rng()) >> shift);
    if (i % 50 == 0) t.d[0] = t.d[1] = 0, t.d[2] = int16_t(-b.cfg.c2 * 64 / int(b.cfg.gain[2]) / 64);
    t.flags = uint8_t(rng() & 0x87);
    in.push_back(t);
  }
  eskin::hls::HallDecouple<0> k(b.cfg);
  std::vector<DecoupleToken> want;
  int valid = 0, invalid = 0;
  for (const auto& t : in) {
    DecoupleToken o;
    if (k.push(t, o)) want.push_back(o), valid += o.valid, invalid += !o.valid;
  }
  auto d = dut(b.cfg);
  auto s = stream();
  s.run(*d, in, 0.6, 0.6, 12);
  ASSERT_EQ(s.outs.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(same(s.outs[i], want[i])) << "token " << i << ": rtl " << s.outs[i].rx << " " << s.outs[i].ry << " "
                                          << s.outs[i].sz << " hls " << want[i].rx << " " << want[i].ry << " " << want[i].sz;
  EXPECT_GT(valid, 600);
  EXPECT_GT(invalid, 50);
}

TEST(HallDecoupleRtl, LatencyFollowsThePrescaleCount) {
  Bench b = make_bench();
  std::vector<HallDeltaToken> in(b.scene.begin(), b.scene.begin() + 40);
  HallDeltaToken g;  // guarded: Bz' < 0
  g.d[2] = -30000;
  in.push_back(g);
  eskin::hls::HallDecouple<0> k(b.cfg);
  auto d = dut(b.cfg);
  auto s = stream();
  s.run(*d, in, 1.0, 1.0, 13);
  ASSERT_EQ(s.out_cycles.size(), in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    DecoupleToken o;
    k.push(in[i], o);
    uint64_t want = 11;  // guarded
    if (o.valid) want = 158 + uint64_t(k.halvings(0) + k.halvings(1) + k.halvings(2));
    ASSERT_EQ(s.out_cycles[i] - s.in_cycles[i], want) << "token " << i;
  }
}

}  // namespace
