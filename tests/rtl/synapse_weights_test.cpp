// rtl/synapse_weights.v against hls/synapse_weights.h: every output token
// bit-exact under random valid/ready back-pressure, random and extreme
// weights written through the configuration port; latency and initiation
// interval asserted in exact cycles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "clocked_dut.h"
#include "Vsynapse_weights.h"
#include "hls/synapse_weights.h"

namespace {

constexpr int kIn = 9, kOut = 9;  // Verilog defaults (OUT_W 16)
using Kernel = eskin::hls::SynapseWeights<kIn, kOut, 16>;
using eskin::hls::SynapseIn;
using eskin::hls::SynapseOut;

struct Dut : ClockedDut<Vsynapse_weights> {
  void reset() {
    m.cfg_we = 0;
    ClockedDut::reset();
  }
  void write_weight(Kernel& k, int i, int j, int16_t w) {
    m.clk = 0;
    m.cfg_we = 1;
    m.cfg_addr = uint32_t(i * kIn + j);
    m.cfg_data = uint16_t(w);
    tick();
    m.cfg_we = 0;
    k.set_weight(i, j, w);
  }
};

// One step's input tokens: every neuron once in random order (plus, now and
// then, an out-of-range index that must be ignored), `last` on the final one.
std::vector<SynapseIn> make_tokens(std::mt19937_64& rng, int steps, double p_spike) {
  std::vector<SynapseIn> in;
  std::bernoulli_distribution spike(p_spike), stray(0.1);
  for (int s = 0; s < steps; ++s) {
    std::vector<int> order(kIn);
    for (int j = 0; j < kIn; ++j) order[size_t(j)] = j;
    std::shuffle(order.begin(), order.end(), rng);
    if (stray(rng)) in.push_back(SynapseIn{uint16_t(kIn + 3), uint32_t(s), true, false});
    for (int j = 0; j < kIn; ++j)
      in.push_back(SynapseIn{uint16_t(order[size_t(j)]), uint32_t(100 + s), spike(rng), j == kIn - 1});
  }
  return in;
}

void run_compare(Dut& d, Kernel& k, const std::vector<SynapseIn>& in, double pv, double pr,
                 uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution vc(pv), rc(pr);
  std::deque<SynapseOut> expected;
  size_t next = 0, steps_done = 0;
  const size_t steps = size_t(std::count_if(in.begin(), in.end(), [](const SynapseIn& t) { return t.last; }));
  while (steps_done < steps) {
    d.m.clk = 0;
    const bool v = next < in.size() && vc(rng);
    d.m.in_valid = v;
    if (next < in.size()) {
      d.m.in_neuron = in[next].neuron;
      d.m.in_t = in[next].t;
      d.m.in_spike = in[next].spike;
      d.m.in_last = in[next].last;
    }
    d.m.out_ready = rc(rng);
    d.m.eval();
    // A step is collected only while no output of the previous one is pending.
    EXPECT_EQ(bool(d.m.in_ready), expected.empty()) << "cycle " << d.cycle;
    if (v && d.m.in_ready) {
      SynapseOut out[kOut];
      const int n = k.push(in[next], out);
      for (int i = 0; i < n; ++i) expected.push_back(out[i]);
      ++next;
    }
    if (d.m.out_valid && d.m.out_ready) {
      EXPECT_FALSE(expected.empty());
      if (expected.empty()) return;
      EXPECT_EQ(int32_t(d.m.out_x), expected.front().x) << "cycle " << d.cycle;
      EXPECT_EQ(d.m.out_t, expected.front().t);
      EXPECT_EQ(bool(d.m.out_last), expected.front().last);
      steps_done += expected.front().last;
      expected.pop_front();
    }
    d.tick();
  }
}

// Bound: bit-exact equality (integer sums, same saturation) on every token.
TEST(SynapseWeightsRtl, RandomWeightsMatchHlsUnderBackpressure) {
  Dut d;
  Kernel k;
  d.reset();
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<int> wd(-32768, 32767);
  for (int i = 0; i < kOut; ++i)
    for (int j = 0; j < kIn; ++j) d.write_weight(k, i, j, int16_t(wd(rng)));
  run_compare(d, k, make_tokens(rng, 400, 0.4), 0.6, 0.5, 2);
  // Extreme weights: sums of several +-2^15 saturate at 16 bits.
  for (int i = 0; i < kOut; ++i)
    for (int j = 0; j < kIn; ++j) d.write_weight(k, i, j, (i + j) % 3 ? int16_t(32767) : int16_t(-32768));
  run_compare(d, k, make_tokens(rng, 200, 0.7), 0.8, 0.7, 3);
}

// Bound: exact cycles with valid/ready always high: the step's closing
// handshake at cycle 0, output i valid from cycle (i + 1) * (N_IN + 2),
// in_ready again the cycle after the last output handshake.
TEST(SynapseWeightsRtl, LatencyAndIntervalExact) {
  Dut d;
  Kernel k;
  d.reset();
  for (int i = 0; i < kOut; ++i) d.write_weight(k, i, i % kIn, int16_t(10 * i + 1));
  uint64_t last_hs = 0;
  std::vector<uint64_t> out_cycles;
  int sent = 0;
  uint64_t ready_again = 0;
  while (ready_again == 0) {
    d.m.clk = 0;
    d.m.in_valid = sent < kIn;
    d.m.in_neuron = uint16_t(sent);
    d.m.in_t = 9;
    d.m.in_spike = 1;
    d.m.in_last = sent == kIn - 1;
    d.m.out_ready = 1;
    d.m.eval();
    if (d.m.in_valid && d.m.in_ready) {
      if (sent == kIn - 1) last_hs = d.cycle;
      ++sent;
    } else if (d.m.in_ready && sent == kIn) {
      ready_again = d.cycle;
    }
    if (d.m.out_valid) {
      out_cycles.push_back(d.cycle);
      EXPECT_EQ(int32_t(d.m.out_x), 10 * int(out_cycles.size() - 1) + 1);
    }
    d.tick();
    ASSERT_LT(d.cycle, 10000u);
  }
  ASSERT_EQ(out_cycles.size(), size_t(kOut));
  for (int i = 0; i < kOut; ++i)
    EXPECT_EQ(out_cycles[size_t(i)] - last_hs, uint64_t((i + 1) * (kIn + 2)));
  EXPECT_EQ(ready_again, out_cycles.back() + 1);
}

}  // namespace
