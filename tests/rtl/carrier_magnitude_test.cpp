// rtl/carrier_magnitude.v against hls/carrier_magnitude.h, token by token.
//
// Bound: bit-exact (k, mag, last equal for every token), because the HLS
// kernel is the executable spec of the module. Checked with random valid
// gaps and random back-pressure (out_ready low up to ~60% of cycles), plus
// the stream rules: out_valid and the output data hold while stalled, and no
// token is lost, duplicated or reordered.
// Timing (header of rtl/carrier_magnitude.v): with in_valid and out_ready
// always high, latency = NB + 8 cycles from the input handshake to the
// output handshake and II = NB + 9 cycles, NB = MAG_W + 1 — asserted exactly.
// Two parameter sets: the default (ACC_W 24, MAG_W 16, SHIFT 8, never
// saturates) and an odd, saturating one (ACC_W 13, MAG_W 8, SHIFT 1), built
// by carrier_magnitude_test.cmake.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <vector>

#include "Vcarrier_magnitude.h"
#include "Vcarrier_magnitude_small.h"
#include "hls/carrier_magnitude.h"

namespace {

struct Token {
  uint8_t k;
  int32_t re, im;
  bool last;
};

template <int ACC_W>
std::vector<Token> make_tokens(int n, uint64_t seed) {
  const int32_t vmax = int32_t((int64_t(1) << (ACC_W - 1)) - 1);
  const int32_t vmin = -vmax - 1;
  std::vector<Token> t;
  const int32_t edge[] = {vmin, vmax, 0, -1, 1};
  for (int32_t a : edge)
    for (int32_t b : edge) t.push_back({uint8_t(t.size() % 6), a, b, t.size() % 6 == 5});
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int32_t> full(vmin, vmax);
  std::uniform_int_distribution<int> bits(0, ACC_W - 1);
  while (int(t.size()) < n) {
    int32_t re = full(rng), im = full(rng);
    if (rng() & 1) {
      const int b = bits(rng);
      re >>= (ACC_W - 1 - b);
      im >>= (ACC_W - 1 - b);
    }
    const uint8_t k = uint8_t(t.size() % 6);
    t.push_back({k, re, im, k == 5});
  }
  return t;
}

struct Stats {
  std::vector<uint64_t> in_cycle, out_cycle;
};

// Runs the tokens through the model; p_valid / p_ready are the per-cycle
// probabilities that the source offers a token / the sink accepts one.
template <class Model, int ACC_W, int MAG_W, int SHIFT>
Stats run(const std::vector<Token>& tokens, double p_valid, double p_ready, uint64_t seed) {
  using Kernel = eskin::hls::CarrierMagnitude<ACC_W, MAG_W, SHIFT>;
  const uint32_t mask = uint32_t((uint64_t(1) << ACC_W) - 1);
  auto m = std::make_unique<Model>();
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution offer(p_valid), accept(p_ready);
  Stats s;
  m->clk = 0;
  m->rst = 1;
  m->in_valid = 0;
  m->out_ready = 0;
  for (int i = 0; i < 4; ++i) {
    m->clk = 0; m->eval();
    m->clk = 1; m->eval();
  }
  m->rst = 0;
  size_t next_in = 0, next_out = 0;
  bool offering = false, was_stalled = false;
  uint32_t held_mag = 0, held_k = 0;
  const uint64_t max_cycles = uint64_t(tokens.size()) * 400 + 1000;
  for (uint64_t cyc = 0; next_out < tokens.size() && cyc < max_cycles; ++cyc) {
    // A source keeps valid (and data) up until the handshake.
    if (!offering && next_in < tokens.size() && offer(rng)) offering = true;
    m->in_valid = offering;
    if (offering) {
      const Token& t = tokens[next_in];
      m->in_k = t.k;
      m->in_re = uint32_t(t.re) & mask;
      m->in_im = uint32_t(t.im) & mask;
      m->in_last = t.last;
    }
    m->out_ready = accept(rng);
    m->clk = 0;
    m->eval();
    if (was_stalled) {  // output held since the stalled cycle
      EXPECT_TRUE(m->out_valid) << "out_valid dropped before the handshake";
      EXPECT_EQ(m->out_mag, held_mag);
      EXPECT_EQ(m->out_k, held_k);
    }
    if (m->in_valid && m->in_ready) {
      s.in_cycle.push_back(cyc);
      ++next_in;
      offering = false;
    }
    was_stalled = m->out_valid && !m->out_ready;
    held_mag = m->out_mag;
    held_k = m->out_k;
    if (m->out_valid && m->out_ready) {
      EXPECT_LT(next_out, next_in) << "output before its input";
      const Token& t = tokens[next_out];
      eskin::hls::CarrierMagnitudeIn in{t.k, t.re, t.im, t.last};
      eskin::hls::CarrierMagnitudeOut want;
      Kernel().push(in, want);
      EXPECT_EQ(m->out_k, want.k) << "token " << next_out;
      EXPECT_EQ(m->out_mag, want.mag) << "token " << next_out << " re=" << t.re << " im=" << t.im;
      EXPECT_EQ(bool(m->out_last), want.last) << "token " << next_out;
      s.out_cycle.push_back(cyc);
      ++next_out;
    }
    m->clk = 1;
    m->eval();
  }
  EXPECT_EQ(next_out, tokens.size()) << "tokens lost or module hung";
  m->final();
  return s;
}

template <class Model, int ACC_W, int MAG_W, int SHIFT>
void check_model(int n_tokens, uint64_t seed) {
  const auto tokens = make_tokens<ACC_W>(n_tokens, seed);
  // Random gaps and back-pressure: bit-exact, protocol respected.
  run<Model, ACC_W, MAG_W, SHIFT>(tokens, 0.5, 0.4, seed + 1);
  run<Model, ACC_W, MAG_W, SHIFT>(tokens, 0.9, 0.9, seed + 2);
  // Free-running: exact latency and initiation interval.
  const Stats s = run<Model, ACC_W, MAG_W, SHIFT>(tokens, 1.0, 1.0, seed + 3);
  const uint64_t nb = MAG_W + 1;
  ASSERT_EQ(s.in_cycle.size(), tokens.size());
  ASSERT_EQ(s.out_cycle.size(), tokens.size());
  for (size_t i = 0; i < tokens.size(); ++i) {
    ASSERT_EQ(s.out_cycle[i] - s.in_cycle[i], nb + 8) << "latency, token " << i;
    if (i > 0) {
      ASSERT_EQ(s.in_cycle[i] - s.in_cycle[i - 1], nb + 9) << "II, token " << i;
    }
  }
}

TEST(CarrierMagnitudeRtl, DefaultParametersBitExact) {
  check_model<Vcarrier_magnitude, 24, 16, 8>(20000, 11);
}

TEST(CarrierMagnitudeRtl, OddWidthSaturatingBitExact) {
  check_model<Vcarrier_magnitude_small, 13, 8, 1>(20000, 21);
}

}  // namespace
