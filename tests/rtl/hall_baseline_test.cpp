// rtl/hall_baseline.v against hls/hall_baseline.h, token by token.
//
// Bound: bit-exact (id, t, dx, dy, dz, flags of every output token; the
// drop counter), because the HLS kernel is the module's executable spec.
// Inputs: the seed-003 scene's device-quantised tokens (two's complement
// codes, default parameters) with no-data and foreign-id tokens mixed in,
// then a loaded baseline and a recapture; a second build
// (hall_baseline_test.cmake: NS 3, ID_BASE 4, capture 2, offset-binary
// codes 0x8000) on random codes reaching both saturation rails.
// Timing: II = 1 and latency 1 cycle with the stream always ready (asserted).
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

TEST(HallBaselineRtl, OneTokenPerCycleLatencyOne) {
  auto data = eskin::test::hall_tokens("hall_003_metamaterial.yaml", 0.2);
  auto d = std::make_unique<ClockedDut<Vhall_baseline>>();
  d->reset();
  auto s = stream<Vhall_baseline>();
  s.run(*d, data.tokens, 1.0, 1.0, 8);
  ASSERT_EQ(s.in_cycles.size(), data.tokens.size());
  for (size_t i = 1; i < s.in_cycles.size(); ++i) ASSERT_EQ(s.in_cycles[i], s.in_cycles[i - 1] + 1);
  // The first 9 * 16 tokens are captured; token i >= 144 leaves one cycle later.
  ASSERT_EQ(s.out_cycles.size(), data.tokens.size() - 144);
  for (size_t i = 0; i < s.out_cycles.size(); ++i) ASSERT_EQ(s.out_cycles[i], s.in_cycles[144 + i] + 1);
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
