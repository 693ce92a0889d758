// rtl/carrier_demix.v against hls/carrier_demix.h, token by token.
//
// Bound: bit-exact (k, re, im, last equal for every output token): the HLS
// kernel is the executable spec. Tables come from the host-side builder
// (hls/carrier_demix_config.h) through the config port; input tokens are
// the 6 + 1 (DC) sums of hls sdft_bank on a random multi-tone signal with
// noise and a DC offset. Random input gaps and output back-pressure check
// the stream rules (outputs hold while stalled, nothing lost or reordered).
// Timing, K = 6 (dim = 2K+1 = 13), both ends always ready (derived from the
// state sequence in the RTL header):
//   each input token occupies 8 cycles (handshake, 2 table reads, 4
//   products, store); after the frame's last token, 1 prefetch cycle, then
//   each output pair of rows takes 2 dim cycles + 1 output cycle, then 1
//   phase-update cycle per carrier. Hence
//   latency (last input handshake -> first output handshake) = 2 dim + 9 = 35,
//   output spacing within a frame = 2 dim + 1 = 27,
//   II per frame = 8 (K+1) + 1 + K (2 dim + 1) + K = 225 cycles;
// the same formulas are asserted for a runtime K = 3 (latency 23, II 81).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "Vcarrier_demix.h"
#include "hls/carrier_demix.h"
#include "hls/carrier_demix_config.h"
#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"

namespace {

constexpr double kFs = 35000;
const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};
constexpr int kK = 6, kN = 32, kDim = 2 * kK + 1;
using Demix = eskin::hls::CarrierDemix<kK, kN>;
using Bank = eskin::hls::SdftBank<kK + 1, kN>;
const double kGs = (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15);

int32_t sext(uint32_t v, int w) { return int32_t(v << (32 - w)) >> (32 - w); }

struct Harness {
  std::unique_ptr<Vcarrier_demix> m = std::make_unique<Vcarrier_demix>();
  uint64_t cycle = 0;
  void tick() {
    m->clk = 0;
    m->eval();
    m->clk = 1;
    m->eval();
    ++cycle;
  }
  void reset() {
    m->rst = 1;
    m->cfg_valid = 0;
    m->in_valid = 0;
    m->out_ready = 0;
    for (int i = 0; i < 4; ++i) tick();
    m->rst = 0;
  }
  void write(int sel, int addr, uint32_t data) {
    m->cfg_valid = 1;
    m->cfg_sel = sel;
    m->cfg_addr = addr;
    m->cfg_data = data;
    for (int guard = 0;; ++guard) {
      m->clk = 0;
      m->eval();
      const bool fire = m->cfg_ready;
      m->clk = 1;
      m->eval();
      ++cycle;
      if (fire) break;
      ASSERT_LT(guard, 1000) << "config port never ready";
    }
    m->cfg_valid = 0;
  }
  void configure(const Demix::Config& c) {
    for (int k = 0; k < c.carriers; ++k) write(0, k, c.inc[k]);
    for (int i = 0; i < Demix::Config::QN; ++i) write(1, i, uint32_t(c.qsin[i]));
    const int dim = 2 * c.carriers + 1;
    for (int i = 0; i < dim * dim; ++i) write(2, i, uint32_t(c.coef[i]));
    write(3, 0, uint32_t(c.carriers));
  }
};

struct Timing {
  std::vector<uint64_t> in_cycle, out_cycle;
};

// Input tokens: hls sdft_bank (6 carriers + DC) on a noisy multi-tone.
std::vector<Demix::Token> make_tokens(int samples, uint64_t seed,
                                      const std::vector<double>& freqs = kThesis) {
  const int nk = int(freqs.size());
  Bank::Config bcfg;
  EXPECT_TRUE(eskin::hls::make_sdft_bank_config<Bank>(freqs, kFs, bcfg).ok());
  bcfg.inc[nk] = 0;
  bcfg.carriers = nk + 1;
  Bank bank;
  EXPECT_TRUE(bank.configure(bcfg));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  double amp[kK], ph[kK];
  for (int k = 0; k < kK; ++k) amp[k] = 1200 * u(rng), ph[k] = 6.283 * u(rng);
  std::vector<Demix::Token> t;
  Bank::Token sums[kK + 1];
  for (int n = 0; n < samples; ++n) {
    double v = 30 + 400 * (u(rng) - 0.5);
    for (int k = 0; k < nk; ++k) v += amp[k] * std::cos(6.283185307 * freqs[k] / kFs * n + ph[k]);
    const int32_t x = int32_t(std::lround(std::max(-4096.0, std::min(4095.0, v))));
    bank.push(x, sums);
    for (int k = 0; k <= nk; ++k) t.push_back({sums[k].k, sums[k].re, sums[k].im, sums[k].last});
  }
  return t;
}

Timing run(const Demix::Config& cfg, const std::vector<Demix::Token>& tokens, double p_valid,
           double p_ready, uint64_t seed) {
  Demix ref;
  EXPECT_TRUE(ref.configure(cfg));
  std::vector<Demix::Token> want;
  Demix::Token out[kK];
  for (const auto& t : tokens) {
    const int n = ref.push(t, out);
    for (int i = 0; i < n; ++i) want.push_back(out[i]);
  }
  Harness h;
  h.reset();
  h.configure(cfg);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution offer(p_valid), accept(p_ready);
  Timing tm;
  size_t next_in = 0, next_out = 0;
  bool offering = false, stalled = false;
  uint32_t held_re = 0, held_im = 0;
  const uint64_t limit = h.cycle + tokens.size() * 200 + 10000;
  while (next_out < want.size() && h.cycle < limit) {
    if (!offering && next_in < tokens.size() && offer(rng)) offering = true;
    h.m->in_valid = offering;
    if (offering) {
      const auto& t = tokens[next_in];
      h.m->in_k = t.k;
      h.m->in_re = uint32_t(t.re) & 0xffffffu;
      h.m->in_im = uint32_t(t.im) & 0xffffffu;
      h.m->in_last = t.last;
    }
    h.m->out_ready = accept(rng);
    h.m->clk = 0;
    h.m->eval();
    if (stalled) {
      EXPECT_TRUE(h.m->out_valid) << "out_valid dropped while stalled";
      EXPECT_EQ(h.m->out_re, held_re);
      EXPECT_EQ(h.m->out_im, held_im);
    }
    if (h.m->in_valid && h.m->in_ready) {
      if (tokens[next_in].last) tm.in_cycle.push_back(h.cycle);
      ++next_in;
      offering = false;
    }
    stalled = h.m->out_valid && !h.m->out_ready;
    held_re = h.m->out_re;
    held_im = h.m->out_im;
    if (h.m->out_valid && h.m->out_ready) {
      const auto& w = want[next_out];
      EXPECT_EQ(h.m->out_k, w.k) << "token " << next_out;
      EXPECT_EQ(sext(h.m->out_re, 24), w.re) << "token " << next_out;
      EXPECT_EQ(sext(h.m->out_im, 24), w.im) << "token " << next_out;
      EXPECT_EQ(bool(h.m->out_last), w.last) << "token " << next_out;
      tm.out_cycle.push_back(h.cycle);
      ++next_out;
      if (::testing::Test::HasFailure()) break;
    }
    h.m->clk = 1;
    h.m->eval();
    ++h.cycle;
  }
  EXPECT_EQ(next_out, want.size()) << "tokens lost or module hung";
  EXPECT_GT(want.size(), tokens.size() / 2);  // outputs were really compared
  return tm;
}

Demix::Config build(const std::vector<double>& freqs = kThesis) {
  Demix::Config cfg;
  const auto st = eskin::hls::make_carrier_demix_config<Demix>(freqs, kFs, kGs, cfg);
  EXPECT_TRUE(st.ok) << st.message;
  return cfg;
}

TEST(CarrierDemixRtl, BitExactUnderBackPressure) {
  const auto cfg = build();
  const auto tokens = make_tokens(600, 3);
  run(cfg, tokens, 0.5, 0.4, 11);
  run(cfg, tokens, 0.95, 0.9, 12);
}

void check_timing(const std::vector<double>& freqs, uint64_t seed) {
  const int k_n = int(freqs.size()), dim = 2 * k_n + 1;
  const auto cfg = build(freqs);
  const auto tokens = make_tokens(300, seed, freqs);
  const Timing tm = run(cfg, tokens, 1.0, 1.0, seed + 1);
  ASSERT_EQ(tm.out_cycle.size(), tm.in_cycle.size() * k_n);
  for (size_t f = 0; f < tm.in_cycle.size(); ++f) {
    ASSERT_EQ(tm.out_cycle[f * k_n] - tm.in_cycle[f], uint64_t(2 * dim + 9)) << "frame " << f;
    for (int k = 1; k < k_n; ++k)
      ASSERT_EQ(tm.out_cycle[f * k_n + k] - tm.out_cycle[f * k_n + k - 1], uint64_t(2 * dim + 1));
    if (f > 0) {
      ASSERT_EQ(tm.in_cycle[f] - tm.in_cycle[f - 1],
                uint64_t(8 * (k_n + 1) + 1 + k_n * (2 * dim + 1) + k_n)) << "frame " << f;
    }
  }
}

TEST(CarrierDemixRtl, ExactLatencyAndInitiationInterval) {
  check_timing(kThesis, 4);  // K = 6: latency 35, II 225
}

// Fewer carriers than K_MAX (runtime K = 3, 2K+1 = 7): the runtime sizes
// (matrix dimension, last token, phase loop) follow the configuration.
TEST(CarrierDemixRtl, FewerCarriersThanKMax) {
  const std::vector<double> three = {1900, 5000, 8300};
  const auto cfg = build(three);
  const auto tokens = make_tokens(400, 5, three);
  run(cfg, tokens, 0.6, 0.5, 21);
  check_timing(three, 6);  // latency 23, II 81
}

}  // namespace
