// rtl/izhikevich_layer.v against hls/izhikevich_layer.h, token by token,
// bit-exact (spike flag and the full state v, U after every update), under
// random valid/ready back-pressure; latency and initiation interval asserted
// in exact cycles. Two parameter sets: the Verilog defaults (RA receptor,
// 9 neurons, dt = 1/35 ms, taxel codes UQ1.15) and an "alt" set verilated by
// izhikevich_layer_test.cmake (RS, 3 neurons, dt = 1 ms, 1 mV/ms per LSB:
// left-shifted gain, J, U and v saturation, U_FRAC = 22).
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <random>

#include "clocked_dut.h"
#include "Vizhikevich_layer.h"
#include "Vizhikevich_layer_alt.h"
#include "hls/izhikevich_layer.h"
#include "hls/izhikevich_layer_config.h"

namespace {

using eskin::hls::IzhikevichConfig;
using eskin::hls::IzhikevichIn;
using eskin::hls::IzhikevichOut;

constexpr int kLatency = 11;  // input handshake -> out_valid (cycles)
constexpr int kII = 12;       // cycles per neuron update, output always ready

template <class V>
struct Dut : ClockedDut<V> {
  using ClockedDut<V>::m;
  using ClockedDut<V>::tick;
  // Reset, then count the initialisation cycles until in_ready.
  int reset() {
    ClockedDut<V>::reset();
    int n = 0;
    for (;;) {
      m.clk = 0;
      m.eval();
      if (m.in_ready) return n;
      tick();
      ++n;
      if (n > 100000) return -1;
    }
  }
};

// Drives `inputs` through the DUT and the HLS model; every output token must
// match. Back-pressure: valid and ready are each high with probability p.
template <class V, int N>
void run_compare(Dut<V>& d, const IzhikevichConfig& cfg, const std::vector<IzhikevichIn>& inputs,
                 double p_valid, double p_ready, uint64_t seed, long* spikes,
                 long* v_at_min = nullptr, long* u_at_max = nullptr) {
  eskin::hls::IzhikevichLayer<N> ref(cfg);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution valid_coin(p_valid), ready_coin(p_ready);
  std::deque<std::pair<IzhikevichOut, uint64_t>> expected;  // token, handshake cycle
  size_t next_in = 0, received = 0;
  bool out_seen_valid = false;
  while (received < inputs.size()) {
    // Drive on the falling edge, then sample and clock.
    d.m.clk = 0;
    const bool v_in = next_in < inputs.size() && valid_coin(rng);
    d.m.in_valid = v_in;
    if (next_in < inputs.size()) {
      d.m.in_x = uint32_t(inputs[next_in].x);
      d.m.in_t = inputs[next_in].t;
    }
    d.m.out_ready = ready_coin(rng);
    d.m.eval();
    // One token in flight at a time: in_ready is high exactly when none is,
    // i.e. from the cycle after the output handshake until the next input.
    EXPECT_EQ(bool(d.m.in_ready), expected.empty()) << "cycle " << d.cycle;
    if (v_in && d.m.in_ready) {
      IzhikevichOut o;
      ref.push(inputs[next_in], o);
      expected.push_back({o, d.cycle});
      ++next_in;
    }
    if (d.m.out_valid) {
      if (!out_seen_valid) {
        EXPECT_FALSE(expected.empty());
        if (expected.empty()) return;
        // First cycle with out_valid: exactly kLatency after the input handshake.
        EXPECT_EQ(d.cycle - expected.front().second, uint64_t(kLatency)) << "token " << received;
        out_seen_valid = true;
      }
      if (d.m.out_ready) {
        const IzhikevichOut& e = expected.front().first;
        EXPECT_EQ(d.m.out_neuron, e.neuron) << "token " << received;
        EXPECT_EQ(d.m.out_t, e.t) << "token " << received;
        EXPECT_EQ(bool(d.m.out_spike), e.spike) << "token " << received;
        EXPECT_EQ(bool(d.m.out_last), e.last) << "token " << received;
        EXPECT_EQ(int32_t(d.m.out_v), e.v) << "token " << received;
        ASSERT_EQ(int32_t(d.m.out_u), e.U) << "token " << received;
        *spikes += e.spike;
        if (v_at_min) *v_at_min += e.v == eskin::hls::izh::kVMin;
        if (u_at_max) *u_at_max += e.U == eskin::hls::izh::kUMax;
        expected.pop_front();
        ++received;
        out_seen_valid = false;
      }
    } else {
      EXPECT_FALSE(out_seen_valid) << "out_valid dropped before the handshake";
    }
    d.tick();
  }
}

IzhikevichConfig default_config() {
  // Verilog defaults: RA, dt = 1/35 ms, g in UQ1.15 scaled by input_scale 10.
  return eskin::hls::make_izhikevich_config(eskin::hls::izhikevich_fixed_preset("RA"), 1.0 / 35.0,
                                            10.0 / 32768.0, 1);
}

IzhikevichConfig alt_config() {
  return eskin::hls::make_izhikevich_config(eskin::hls::izhikevich_fixed_preset("RS"), 1.0, 1.0, 0);
}

// Inputs for `steps` layer steps of N neurons: per neuron a level held for a
// random number of steps (so neurons do fire), drawn from `levels` or
// uniformly from [lo, hi].
std::vector<IzhikevichIn> make_inputs(int n, int steps, int32_t lo, int32_t hi,
                                      const std::vector<int32_t>& extremes, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int32_t> level(lo, hi);
  std::uniform_int_distribution<int> hold(1, 400);
  std::uniform_int_distribution<size_t> pick(0, extremes.size());
  std::vector<int32_t> cur(size_t(n), 0);
  std::vector<int> left(size_t(n), 0);
  std::vector<IzhikevichIn> in;
  for (int s = 0; s < steps; ++s)
    for (int i = 0; i < n; ++i) {
      if (left[size_t(i)]-- <= 0) {
        const size_t e = pick(rng);
        cur[size_t(i)] = e < extremes.size() ? extremes[e] : level(rng);
        left[size_t(i)] = hold(rng);
      }
      in.push_back(IzhikevichIn{cur[size_t(i)], uint32_t(1000 + s)});
    }
  return in;
}

// Bound: bit-exact equality of every output token (neuron, t, spike, last,
// v, U) under random back-pressure: the RTL implements the same integer
// function as the HLS spec, so any difference is a bug.
TEST(IzhikevichLayerRtl, DefaultMatchesHlsUnderBackpressure) {
  Dut<Vizhikevich_layer> d;
  ASSERT_EQ(d.reset(), 9);  // N cycles of state initialisation
  const auto in = make_inputs(9, 3000, 0, 65535, {0, 65535, INT32_MAX, INT32_MIN}, 1);
  long spikes = 0;
  run_compare<Vizhikevich_layer, 9>(d, default_config(), in, 0.7, 0.6, 2, &spikes);
  EXPECT_GT(spikes, 500);  // the stream exercised spiking, not just rest
}

TEST(IzhikevichLayerRtl, AltParametersMatchHls) {
  // The alt model's parameters (izhikevich_layer_test.cmake) must be what
  // the builder gives for RS, dt = 1 ms, 1 mV/ms per LSB.
  const IzhikevichConfig c = alt_config();
  EXPECT_EQ(c.v_init, IZH_ALT_V_INIT);
  EXPECT_EQ(c.u_init, IZH_ALT_U_INIT);
  EXPECT_EQ(c.v_reset, IZH_ALT_V_RESET);
  EXPECT_EQ(c.u_jump, IZH_ALT_U_JUMP);
  EXPECT_EQ(c.u_frac, IZH_ALT_U_FRAC);
  EXPECT_EQ(c.c_const, IZH_ALT_C_CONST);
  EXPECT_EQ(c.m2, IZH_ALT_M2);
  EXPECT_EQ(c.s2, IZH_ALT_S2);
  EXPECT_EQ(c.m3, IZH_ALT_M3);
  EXPECT_EQ(c.s3, IZH_ALT_S3);
  EXPECT_EQ(c.m4, IZH_ALT_M4);
  EXPECT_EQ(c.s4, IZH_ALT_S4);
  EXPECT_EQ(c.gain, IZH_ALT_GAIN);
  EXPECT_EQ(c.gain_shift, IZH_ALT_GAIN_SHIFT);
  EXPECT_EQ(c.x_shift, IZH_ALT_X_SHIFT);
  Dut<Vizhikevich_layer_alt> d;
  ASSERT_EQ(d.reset(), IZH_ALT_N);
  const auto in = make_inputs(IZH_ALT_N, 4000, -40, 60,
                              {0, 1000, -1000, 32767, -32768, INT32_MAX, INT32_MIN}, 3);
  long spikes = 0, v_at_min = 0, u_at_max = 0;
  run_compare<Vizhikevich_layer_alt, IZH_ALT_N>(d, c, in, 0.5, 0.5, 4, &spikes, &v_at_min,
                                                &u_at_max);
  EXPECT_GT(spikes, 500);
  EXPECT_GT(v_at_min, 0);  // the v saturation path was exercised
  EXPECT_GT(u_at_max, 0);  // and the U one
}

// Bound: exact cycle counts with valid and ready always high: handshakes
// every kII = 12 cycles, out_valid kLatency = 11 cycles after each, so one
// layer step of N neurons takes 12 N cycles.
TEST(IzhikevichLayerRtl, LatencyAndInitiationIntervalExact) {
  Dut<Vizhikevich_layer> d;
  ASSERT_EQ(d.reset(), 9);
  std::vector<uint64_t> in_hs, out_first;
  bool prev_valid = false;
  const int tokens = 9 * 5;
  int sent = 0;
  while (int(out_first.size()) < tokens) {
    d.m.clk = 0;
    d.m.in_valid = sent < tokens;
    d.m.in_x = 30000;
    d.m.in_t = 7;
    d.m.out_ready = 1;
    d.m.eval();
    if (d.m.in_valid && d.m.in_ready) {
      in_hs.push_back(d.cycle);
      ++sent;
    }
    if (d.m.out_valid && !prev_valid) out_first.push_back(d.cycle);
    prev_valid = d.m.out_valid;
    d.tick();
  }
  for (int i = 0; i < tokens; ++i) {
    EXPECT_EQ(out_first[size_t(i)] - in_hs[size_t(i)], uint64_t(kLatency));
    if (i > 0) {
      EXPECT_EQ(in_hs[size_t(i)] - in_hs[size_t(i - 1)], uint64_t(kII));
    }
  }
  EXPECT_EQ(in_hs[9] - in_hs[0], uint64_t(9 * kII));  // one layer step
}

}  // namespace
