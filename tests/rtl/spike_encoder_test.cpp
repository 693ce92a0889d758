// rtl/spike_encoder.v against hls/spike_encoder.h: every word bit-exact under
// random valid/ready back-pressure, non-spike tokens dropped; LATENCY 1 and
// II 1 asserted in exact cycles.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <random>

#include "clocked_dut.h"
#include "Vspike_encoder.h"
#include "hls/spike_encoder.h"

namespace {

using eskin::hls::SpikeEncoderIn;

using Dut = ClockedDut<Vspike_encoder>;

// Bound: bit-exact words (pure packing), same order, none lost or invented.
TEST(SpikeEncoderRtl, MatchesHlsUnderBackpressure) {
  Dut d;
  d.reset();
  eskin::hls::SpikeEncoder<4, 12> enc;
  std::mt19937_64 rng(1);
  std::bernoulli_distribution vc(0.7), rc(0.6), sc(0.5);
  std::deque<uint64_t> expected;
  SpikeEncoderIn cur{uint8_t(rng() & 15), uint16_t(rng() & 4095), uint32_t(rng()), sc(rng)};
  long sent = 0, words = 0;
  while (sent < 200000 || !expected.empty()) {
    d.m.clk = 0;
    const bool v = sent < 200000 && vc(rng);
    d.m.in_valid = v;
    d.m.in_layer = cur.layer;
    d.m.in_neuron = cur.neuron;
    d.m.in_t = cur.t;
    d.m.in_spike = cur.spike;
    d.m.out_ready = rc(rng);
    d.m.eval();
    if (d.m.out_valid && d.m.out_ready) {
      ASSERT_FALSE(expected.empty()) << "word without a spike, cycle " << d.cycle;
      ASSERT_EQ(uint64_t(d.m.out_word), expected.front()) << "cycle " << d.cycle;
      expected.pop_front();
      ++words;
    }
    if (v && d.m.in_ready) {
      uint64_t w = 0;
      if (enc.push(cur, w)) expected.push_back(w);
      ++sent;
      cur = SpikeEncoderIn{uint8_t(rng() & 15), uint16_t(rng() & 4095), uint32_t(rng()), sc(rng)};
    }
    d.tick();
    ASSERT_LT(d.cycle, 2000000u);
  }
  EXPECT_GT(words, 80000);
}

// Bound: with valid/ready always high and every token a spike, one handshake
// per cycle (II 1) and each word valid exactly one cycle after its input.
TEST(SpikeEncoderRtl, LatencyOneIntervalOne) {
  Dut d;
  d.reset();
  for (uint32_t k = 0; k < 50; ++k) {
    d.m.clk = 0;
    d.m.in_valid = 1;
    d.m.in_layer = 1;
    d.m.in_neuron = 5;
    d.m.in_t = k;
    d.m.in_spike = 1;
    d.m.out_ready = 1;
    d.m.eval();
    EXPECT_TRUE(d.m.in_ready);
    if (k > 0) {
      ASSERT_TRUE(d.m.out_valid);
      EXPECT_EQ(uint64_t(d.m.out_word), (uint64_t(k - 1) << 16) | (1u << 12) | 5u);
    } else {
      EXPECT_FALSE(d.m.out_valid);
    }
    d.tick();
  }
}

}  // namespace
