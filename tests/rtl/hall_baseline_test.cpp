// rtl/hall_baseline.v against hls/hall_baseline.h, token by token.
//
// Bound: bit-exact (id, t, dx, dy, dz, flags of every output token; the
// drop counter), because the HLS kernel is the module's executable spec.
// Inputs: the seed-003 scene's device-quantised tokens (two's complement
// codes, default parameters) with no-data and foreign-id tokens mixed in,
// then a loaded baseline and a recapture; a second build
// (hall_baseline_test.cmake: NS 3, ID_BASE 4, capture 2, offset-binary
// codes 0x8000) on random codes reaching both saturation rails.
// Commands (set, recapture) given at random cycles while tokens flow, the
// HLS kernel applying each after the tokens taken up to its cycle.
// Timing: II = 2 for data tokens, 1 for dropped ones, latency 2 cycles with
// the stream always ready (asserted).
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "Vhall_baseline.h"
#include "Vhall_baseline_off.h"
#include "hall_stream.h"
#include "hls/hall_baseline.h"
#include "tests/hls/hall_chain_data.h"

namespace {

using eskin::hls::HallDeltaToken;
using eskin::hls::HallSampleToken;

struct OutTok {
  uint8_t id;
  uint32_t t;
  int16_t d[3];
  uint8_t flags;
};
bool same(const OutTok& a, const OutTok& b) {
  return a.id == b.id && a.t == b.t && a.d[0] == b.d[0] && a.d[1] == b.d[1] && a.d[2] == b.d[2] &&
         a.flags == b.flags;
}

template <class V>
HallStream<V, HallSampleToken, OutTok> stream() {
  HallStream<V, HallSampleToken, OutTok> s;
  s.drive = [](V& m, const HallSampleToken& t) {
    m.in_id = t.id, m.in_t = t.t, m.in_x = t.x, m.in_y = t.y, m.in_z = t.z, m.in_flags = t.flags;
  };
  s.read = [](const V& m) {
    return OutTok{uint8_t(m.out_id), uint32_t(m.out_t), {int16_t(m.out_dx), int16_t(m.out_dy), int16_t(m.out_dz)},
                  uint8_t(m.out_flags)};
  };
  s.same = same;
  return s;
}

template <class Kernel>
std::vector<OutTok> expected(Kernel& k, const std::vector<HallSampleToken>& in) {
  std::vector<OutTok> out;
  for (const auto& t : in) {
    HallDeltaToken d;
    if (k.push(t, d)) out.push_back({d.id, d.t, {d.d[0], d.d[1], d.d[2]}, d.flags});
  }
  return out;
}

void expect_equal(const std::vector<OutTok>& got, const std::vector<OutTok>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(same(got[i], want[i])) << "token " << i;
}

TEST(HallBaselineRtl, BitExactOnSceneTokensWithDropsAndCommands) {
  auto data = eskin::test::hall_tokens("hall_003_metamaterial.yaml", 0.6);
  std::vector<HallSampleToken> in = data.tokens;
  for (size_t i = 7; i < in.size(); i += 97) in[i].flags = uint8_t(0x08 << (i % 4));  // no data
  for (size_t i = 11; i < in.size(); i += 131) in[i].id = 200;                        // foreign id
  eskin::hls::HallBaseline<16, 4> k;
  const auto want = expected(k, in);
  auto d = std::make_unique<ClockedDut<Vhall_baseline>>();
  d->reset();
  auto s = stream<Vhall_baseline>();
  s.run(*d, in, 0.8, 0.6, 5);
  expect_equal(s.outs, want);
  EXPECT_EQ(d->m.dropped, k.dropped());
  // Loaded baselines, then a recapture.
  d->m.set_valid = 1, d->m.set_sensor = 2, d->m.set_axis = 1, d->m.set_value = uint16_t(-1234);
  d->tick();
  d->m.set_valid = 0;
  k.set(2, 1, -1234);
  std::vector<HallSampleToken> more(data.tokens.begin(), data.tokens.begin() + 90);
  auto s2 = stream<Vhall_baseline>();
  s2.run(*d, more, 1.0, 1.0, 6);
  expect_equal(s2.outs, expected(k, more));
  d->m.recapture = 1;
  d->tick();
  d->m.recapture = 0;
  k.recapture();
  auto s3 = stream<Vhall_baseline>();
  s3.run(*d, more, 1.0, 0.7, 7);
  expect_equal(s3.outs, expected(k, more));
  EXPECT_GT(s.outs.size(), 2000u);
}

TEST(HallBaselineRtl, TwoCyclesPerDataTokenLatencyTwo) {
  auto data = eskin::test::hall_tokens("hall_003_metamaterial.yaml", 0.2);
  std::vector<HallSampleToken> in = data.tokens;
  for (size_t i = 5; i < in.size(); i += 7) in[i].flags = 0x10;  // no data: dropped
  auto d = std::make_unique<ClockedDut<Vhall_baseline>>();
  d->reset();
  auto s = stream<Vhall_baseline>();
  s.run(*d, in, 1.0, 1.0, 8);
  ASSERT_EQ(s.in_cycles.size(), in.size());
  // A data token holds the RAM read/write-back pipeline for 2 cycles (the
  // handshake reads the sensor's words, the next cycle writes them back);
  // a dropped token needs no state, so the next one follows in 1.
  for (size_t i = 1; i < s.in_cycles.size(); ++i) {
    const bool dropped = (in[i - 1].flags & 0x78) != 0;
    ASSERT_EQ(s.in_cycles[i], s.in_cycles[i - 1] + (dropped ? 1u : 2u)) << "token " << i;
  }
  // Each of the scene's 9 sensors captures its first 16 data tokens; every
  // later data token leaves 2 cycles after its handshake (RAM read, then
  // compute into the output register).
  std::vector<int> seen(256, 0);
  std::vector<uint64_t> want_out;
  for (size_t i = 0; i < in.size(); ++i) {
    if (in[i].flags & 0x78) continue;
    if (++seen[in[i].id] > 16) want_out.push_back(s.in_cycles[i] + 2);
  }
  ASSERT_GT(want_out.size(), 100u);
  ASSERT_EQ(s.out_cycles, want_out);
}

TEST(HallBaselineRtl, CommandsDuringTheStream) {
  auto data = eskin::test::hall_tokens("hall_003_metamaterial.yaml", 0.6);
  const std::vector<HallSampleToken>& in = data.tokens;
  // Per cycle: maybe a set (random sensor, axis 0..3 where 3 is ignored,
  // value) or, rarely, a recapture, both also in cycles where a token is in
  // its second (write-back) cycle or being taken.
  struct Cmd {
    uint64_t cycle;
    bool recapture;
    int sensor, axis;
    int16_t value;
  };
  std::vector<Cmd> cmds;
  std::mt19937_64 rng(12);
  auto d = std::make_unique<ClockedDut<Vhall_baseline>>();
  d->reset();
  auto s = stream<Vhall_baseline>();
  s.every_cycle = [&](Vhall_baseline& m) {
    m.set_valid = 0, m.recapture = 0;
    const uint64_t r = rng() % 1000;
    if (r < 2) {
      m.recapture = 1;
      cmds.push_back({d->cycle, true, 0, 0, 0});
    } else if (r < 40) {
      const Cmd c{d->cycle, false, int(rng() % 10), int(rng() % 4), int16_t(rng())};
      m.set_valid = 1, m.set_sensor = uint8_t(c.sensor), m.set_axis = uint8_t(c.axis);
      m.set_value = uint16_t(c.value);
      cmds.push_back(c);
    }
  };
  s.run(*d, in, 0.7, 0.7, 13);
  ASSERT_EQ(s.in_cycles.size(), in.size());
  // The kernel in cycle order, a cycle's token before its command.
  eskin::hls::HallBaseline<16, 4> k;
  std::vector<OutTok> want;
  size_t c = 0;
  int recaptures = 0;
  auto apply = [&](const Cmd& x) {
    if (x.recapture) k.recapture(), ++recaptures;
    else if (x.axis != 3) k.set(x.sensor, x.axis, x.value);
  };
  for (size_t i = 0; i < in.size(); ++i) {
    while (c < cmds.size() && cmds[c].cycle < s.in_cycles[i]) apply(cmds[c++]);
    HallDeltaToken o;
    if (k.push(in[i], o)) want.push_back({o.id, o.t, {o.d[0], o.d[1], o.d[2]}, o.flags});
  }
  expect_equal(s.outs, want);
  EXPECT_GE(recaptures, 3);
  EXPECT_GT(want.size(), 1000u);
}

TEST(HallBaselineRtl, OffsetBinaryBuildSaturates) {
  // NS 3, ID_BASE 4, CAPTURE_LOG2 1, all offsets 0x8000.
  std::mt19937_64 rng(3);
  std::vector<HallSampleToken> in;
  for (int i = 0; i < 3000; ++i) {
    HallSampleToken t;
    t.id = uint8_t(3 + rng() % 5);  // 3 and 7 are foreign
    t.t = uint32_t(i);
    const uint16_t pick[] = {0x0000, 0xFFFF, 0x8000, uint16_t(rng())};
    t.x = pick[rng() % 4], t.y = pick[rng() % 4], t.z = uint16_t(rng());
    t.flags = (rng() % 10 == 0) ? 0x10 : uint8_t(rng() & 0x87);
    in.push_back(t);
  }
  eskin::hls::HallBaselineConfig c;
  c.offset[0] = c.offset[1] = c.offset[2] = 0x8000;
  eskin::hls::HallBaseline<3, 1, 4> k(c);
  const auto want = expected(k, in);
  auto d = std::make_unique<ClockedDut<Vhall_baseline_off>>();
  d->reset();
  auto s = stream<Vhall_baseline_off>();
  s.run(*d, in, 0.7, 0.5, 9);
  expect_equal(s.outs, want);
  EXPECT_EQ(d->m.dropped, k.dropped());
  int rails = 0;
  for (const auto& o : want) rails += (o.d[0] == 32767 || o.d[0] == -32768);
  EXPECT_GT(rails, 10);
}

}  // namespace
