// rtl/carrier_magnitude.v against hls/carrier_magnitude.h, token by token.
//
// Bound: bit-exact (k, mag, last of every token) with
// CarrierMagnitude<ACC_W, MAG_W, SHIFT>::push at three parameter sets
// (tests/rtl/carrier_magnitude_test.cmake), under random input gaps and
// output back-pressure (seeded; tests/rtl/hall_stream.h also checks that a
// stalled output holds its token). Inputs: frames of K carriers (K = 6, the
// 3x3 skin, and K = 128, a 64x64 skin; last on k = K - 1) with random
// re, im over the whole signed ACC_W range at random scales, the edges (0,
// +-1, the largest positive and the most negative value, all their pairs),
// rounding ties (sqrt(P) / 2^SHIFT = n + 1/2) and, where the set allows it,
// saturation.
// Timing: without back-pressure one carrier a clock in and out, each
// MAG_W + 5 clocks after it was taken (the pipeline in the module header).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "Vcarrier_magnitude.h"
#include "Vcarrier_magnitude_s0.h"
#include "Vcarrier_magnitude_w32.h"
#include "hall_stream.h"
#include "hls/carrier_magnitude.h"

namespace {

using eskin::hls::CarrierMagnitudeIn;
using eskin::hls::CarrierMagnitudeOut;

bool same(const CarrierMagnitudeOut& a, const CarrierMagnitudeOut& b) {
  return a.k == b.k && a.mag == b.mag && a.last == b.last;
}

template <class V, int ACC_W>
HallStream<V, CarrierMagnitudeIn, CarrierMagnitudeOut> stream() {
  HallStream<V, CarrierMagnitudeIn, CarrierMagnitudeOut> s;
  s.drive = [](V& m, const CarrierMagnitudeIn& t) {
    const uint32_t mask = ACC_W == 32 ? 0xFFFFFFFFu : (uint32_t(1) << ACC_W) - 1u;
    m.in_k = t.k, m.in_last = t.last;
    m.in_re = uint32_t(t.re) & mask, m.in_im = uint32_t(t.im) & mask;
  };
  s.read = [](const V& m) {
    CarrierMagnitudeOut o;
    o.k = m.out_k, o.mag = m.out_mag, o.last = m.out_last;
    return o;
  };
  s.same = same;
  return s;
}

// Frames of K carriers: random values, then every pair of edge values,
// then ties, spread over the frames in order.
template <int ACC_W, int SHIFT>
std::vector<CarrierMagnitudeIn> inputs(int K, int frames, uint64_t seed) {
  const int64_t hi = (int64_t(1) << (ACC_W - 1)) - 1, lo = -(int64_t(1) << (ACC_W - 1));
  std::vector<int64_t> edges = {0, 1, -1, hi, lo, hi - 1, lo + 1, hi / 2, lo / 2};
  std::vector<std::pair<int64_t, int64_t>> vals;
  for (int64_t a : edges)
    for (int64_t b : edges) vals.push_back({a, b});
  // Ties: sqrt(re^2) / 2^SHIFT = n + 1/2 when re = (2n + 1) 2^(SHIFT-1).
  if (SHIFT >= 1)
    for (int64_t n = 0; n < 40; ++n) {
      const int64_t re = (2 * n + 1) << (SHIFT - 1);
      if (re <= hi) vals.push_back({re, 0}), vals.push_back({0, -re});
    }
  std::mt19937_64 rng(seed);
  const int total = K * frames;
  while (int(vals.size()) < total) {
    const int sh = int(rng() % uint64_t(ACC_W));
    const int64_t re = int64_t(uint64_t(rng()) << (64 - ACC_W)) >> (64 - ACC_W + sh);
    const int sh2 = rng() % 4 == 0 ? int(rng() % uint64_t(ACC_W)) : sh;
    const int64_t im = int64_t(uint64_t(rng()) << (64 - ACC_W)) >> (64 - ACC_W + sh2);
    vals.push_back({re, im});
  }
  // The edges and ties land at random places in the stream.
  std::shuffle(vals.begin(), vals.end(), rng);
  std::vector<CarrierMagnitudeIn> in;
  for (int f = 0; f < frames; ++f)
    for (int k = 0; k < K; ++k) {
      CarrierMagnitudeIn t;
      const auto& v = vals[size_t(f * K + k)];
      t.k = uint8_t(k), t.re = int32_t(v.first), t.im = int32_t(v.second), t.last = k == K - 1;
      in.push_back(t);
    }
  return in;
}

struct Seen {
  size_t tokens = 0, saturated = 0, zero = 0, lasts = 0;
};

template <class V, int ACC_W, int MAG_W, int SHIFT>
Seen bit_exact(int K, int frames, double p_valid, double p_ready, uint64_t seed) {
  using Kernel = eskin::hls::CarrierMagnitude<ACC_W, MAG_W, SHIFT>;
  const Kernel kernel;
  const auto in = inputs<ACC_W, SHIFT>(K, frames, seed);
  std::vector<CarrierMagnitudeOut> want;
  for (const auto& t : in) {
    CarrierMagnitudeOut o;
    EXPECT_TRUE(kernel.push(t, o));
    want.push_back(o);
  }
  ClockedDut<V> d;
  d.reset();
  auto st = stream<V, ACC_W>();
  st.run(d, in, p_valid, p_ready, seed + 1);
  Seen seen;
  EXPECT_EQ(st.outs.size(), want.size());
  for (size_t i = 0; i < want.size() && i < st.outs.size(); ++i) {
    if (!same(st.outs[i], want[i])) {
      ADD_FAILURE() << "token " << i << " (re " << in[i].re << ", im " << in[i].im << "): rtl k "
                    << int(st.outs[i].k) << " mag " << st.outs[i].mag << " last " << st.outs[i].last
                    << ", hls k " << int(want[i].k) << " mag " << want[i].mag << " last " << want[i].last;
      break;
    }
    ++seen.tokens;
    seen.saturated += want[i].mag == Kernel::MAG_MAX;
    seen.zero += want[i].mag == 0;
    seen.lasts += want[i].last;
  }
  return seen;
}

TEST(CarrierMagnitudeRtl, BitExactDefault3x3UnderBackPressure) {
  const Seen s = bit_exact<Vcarrier_magnitude, 24, 16, 8>(6, 600, 0.7, 0.6, 11);
  EXPECT_EQ(s.tokens, 3600u);
  EXPECT_EQ(s.lasts, 600u);
  EXPECT_GT(s.zero, 0u);
  EXPECT_EQ(s.saturated, 0u);  // SHIFT = ACC_W - MAG_W: never (kernel header)
}

TEST(CarrierMagnitudeRtl, BitExactDefault64x64UnderBackPressure) {
  const Seen s = bit_exact<Vcarrier_magnitude, 24, 16, 8>(128, 40, 0.9, 0.35, 12);
  EXPECT_EQ(s.tokens, 5120u);
  EXPECT_EQ(s.lasts, 40u);
}

TEST(CarrierMagnitudeRtl, BitExactWidestSaturating) {
  const Seen s = bit_exact<Vcarrier_magnitude_w32, 32, 30, 1>(128, 30, 0.6, 0.7, 13);
  EXPECT_EQ(s.tokens, 3840u);
  EXPECT_GT(s.saturated, 50u);
  EXPECT_LT(s.saturated, s.tokens / 2);
}

TEST(CarrierMagnitudeRtl, BitExactShiftZeroSaturating) {
  const Seen s = bit_exact<Vcarrier_magnitude_s0, 20, 16, 0>(6, 500, 0.5, 0.5, 14);
  EXPECT_EQ(s.tokens, 3000u);
  EXPECT_GT(s.saturated, 50u);
  EXPECT_LT(s.saturated, s.tokens);
}

// No gaps, no back-pressure: a carrier every clock in and out, each out
// MAG_W + 5 clocks after it went in.
template <class V, int ACC_W, int SHIFT>
void one_a_clock(int latency) {
  const auto in = inputs<ACC_W, SHIFT>(128, 4, 21);
  ClockedDut<V> d;
  d.reset();
  auto st = stream<V, ACC_W>();
  st.run(d, in, 1.0, 1.0, 22);
  ASSERT_EQ(st.in_cycles.size(), in.size());
  ASSERT_EQ(st.out_cycles.size(), in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    ASSERT_EQ(st.in_cycles[i], st.in_cycles[0] + i) << "input " << i << " not taken on its clock";
    ASSERT_EQ(st.out_cycles[i], st.in_cycles[i] + uint64_t(latency)) << "token " << i;
  }
}

TEST(CarrierMagnitudeRtl, OneCarrierAClockLatencyMagWPlus5) {
  one_a_clock<Vcarrier_magnitude, 24, 8>(21);
  one_a_clock<Vcarrier_magnitude_w32, 32, 1>(35);
  one_a_clock<Vcarrier_magnitude_s0, 20, 0>(21);
}

// A stalled output stops the input too (in_ready low) and loses nothing:
// hold out_ready low for 50 clocks with the input offered.
TEST(CarrierMagnitudeRtl, StallHoldsInputAndOutput) {
  ClockedDut<Vcarrier_magnitude> d;
  d.reset();
  auto& m = d.m;
  m.in_valid = 1, m.in_re = 3000, m.in_im = 4000, m.in_k = 5, m.in_last = 1;
  m.out_ready = 0;
  int taken = 0;
  for (int c = 0; c < 60; ++c) {
    m.eval();
    taken += m.in_ready;
    d.tick();
  }
  // Taken on clocks 0..20; out_valid rose on clock 21 with the first
  // carrier and nothing more was taken: the 21 registers full and held.
  EXPECT_EQ(taken, 21);
  EXPECT_TRUE(m.out_valid);
  EXPECT_EQ(m.out_k, 5);
  // 5000 / 2^8 = 19.53 -> 20.
  EXPECT_EQ(m.out_mag, 20u);
  EXPECT_TRUE(m.out_last);
}

// A one-clock reset with the pipeline full and stalled empties it: nothing
// of before comes out after, and the next stream is bit-exact.
TEST(CarrierMagnitudeRtl, ResetMidFrameEmptiesThePipeline) {
  ClockedDut<Vcarrier_magnitude> d;
  d.reset();
  auto& m = d.m;
  m.in_valid = 1, m.in_re = 12345, m.in_im = -999, m.in_k = 3, m.in_last = 0;
  m.out_ready = 0;
  for (int c = 0; c < 40; ++c) d.tick();
  m.eval();
  ASSERT_TRUE(m.out_valid);
  m.in_valid = 0;
  m.rst = 1;
  d.tick();
  m.rst = 0;
  m.eval();
  EXPECT_FALSE(m.out_valid);
  const auto in = inputs<24, 8>(6, 50, 23);
  const eskin::hls::CarrierMagnitude<24, 16, 8> kernel;
  auto st = stream<Vcarrier_magnitude, 24>();
  st.run(d, in, 0.8, 0.8, 24);
  ASSERT_EQ(st.outs.size(), in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    CarrierMagnitudeOut o;
    kernel.push(in[i], o);
    ASSERT_TRUE(same(st.outs[i], o)) << "token " << i;
  }
}

}  // namespace
