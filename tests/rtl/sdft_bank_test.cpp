// rtl/sdft_bank.v against hls/sdft_bank.h, token by token.
//
// Bound: bit-exact ({k, re, im, last} equal for every token, in order),
// because the HLS kernel is the executable spec of the module. Checked with
// random gaps on in_valid and cfg_valid and random back-pressure on
// out_ready, plus the stream rules (out_valid and the token hold while not
// taken; no token lost, duplicated or reordered), on random full-scale input
// (>= 10^5 samples), on the default scene's ADC samples, and across a
// reconfiguration (the config port's last token clears all state, like
// SdftBank::configure()).
// Timing (header of rtl/sdft_bank.v): with in_valid and out_ready always
// high, token k of a sample is taken 8 + 6 k cycles after that sample's
// input handshake (latency 8) and samples are accepted every 6 K + 2 cycles
// (II) — asserted exactly, also for one carrier (K = 1: II 8, carrier 0's
// state read back the clock after its write-back).
// Two parameter sets: the default (K_MAX 6, N 32, XW 13, CW 16, TW 10,
// ACC_W 24) and an odd one built by sdft_bank_test.cmake (K_MAX 8 with 5
// carriers, N 48 — not a power of two —, XW 12, CW 12, TW 8, FB 2 term
// fraction bits, ACC_W 21, the narrowest legal accumulator).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "Vsdft_bank.h"
#include "Vsdft_bank_odd.h"
#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"
#include "sdft_port.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

using eskin::hls::SdftBank;
using eskin::hls::SdftBankToken;

constexpr double kFs = 35000;

using sdft_port::random_samples;

struct Segment {
  std::vector<double> freqs;
  std::vector<int32_t> xs;
};

struct Timing {
  std::vector<uint64_t> in_cycle, out_cycle;
};

template <class V, class Bank, int XW, int ACC_W>
class Harness {
 public:

  // Drives every segment (config, then samples) with the given probabilities
  // of in_valid/cfg_valid being offered and out_ready being high per cycle.
  void run(const std::vector<Segment>& segs, double p_valid, double p_ready, uint64_t seed,
           Timing* timing = nullptr) {
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution offer(p_valid), ready(p_ready);
    // Expected tokens, per segment, from the HLS kernel.
    std::vector<SdftBankToken> expect;
    for (const Segment& s : segs) {
      typename Bank::Config cfg;
      const auto st = eskin::hls::make_sdft_bank_config<Bank>(s.freqs, kFs, cfg);
      ASSERT_TRUE(st.ok()) << st.message;
      bank_.configure(cfg);
      SdftBankToken out[sizeof(cfg.inc) / sizeof(cfg.inc[0])];
      for (int32_t x : s.xs) {
        const int n = bank_.push(x, out);
        expect.insert(expect.end(), out, out + n);
      }
    }
    size_t got = 0, seg = 0, cfg_sent = 0, x_sent = 0;
    bool held = false;  // an output token was offered and not taken last cycle
    SdftBankToken held_tok{};
    const uint64_t limit = port_.cycle + 400 * (expect.size() + 1000);
    while (got < expect.size()) {
      ASSERT_LT(port_.cycle, limit) << "stalled: " << got << " of " << expect.size() << " tokens";
      const Segment* s = seg < segs.size() ? &segs[seg] : nullptr;
      const bool cfg_phase = s && cfg_sent < s->freqs.size();
      // A new config may be sent only after every earlier sample was taken
      // and its tokens came out (the kernel's configure() is between pushes).
      const bool cfg_allowed = cfg_phase && got == expected_before(segs, seg);
      m_->cfg_valid = cfg_allowed && offer(rng);
      if (cfg_allowed) {
        const uint32_t inc = eskin::hls::sdft_phase_increment(s->freqs[cfg_sent], kFs);
        m_->cfg_k = uint32_t(cfg_sent);
        m_->cfg_inc = inc;
        m_->cfg_last = cfg_sent + 1 == s->freqs.size();
      }
      const bool x_phase = s && !cfg_phase && x_sent < s->xs.size();
      m_->in_valid = x_phase && offer(rng);
      if (x_phase) m_->in_x = uint32_t(s->xs[x_sent]) & ((1u << XW) - 1);
      m_->out_ready = ready(rng);
      m_->clk = 0;
      m_->eval();
      // Stream rule: a token offered but not taken is offered again unchanged.
      if (held) {
        ASSERT_TRUE(m_->out_valid) << "out_valid dropped before the handshake";
        ASSERT_EQ(port_.token().re, held_tok.re);
        ASSERT_EQ(port_.token().im, held_tok.im);
        ASSERT_EQ(port_.token().k, held_tok.k);
      }
      if (m_->out_valid && m_->out_ready) {
        const SdftBankToken t = port_.token(), &e = expect[got];
        ASSERT_EQ(t.k, e.k) << "token " << got;
        ASSERT_EQ(t.re, e.re) << "token " << got << " k " << int(e.k);
        ASSERT_EQ(t.im, e.im) << "token " << got << " k " << int(e.k);
        ASSERT_EQ(t.last, e.last) << "token " << got;
        if (timing) timing->out_cycle.push_back(port_.cycle);
        ++got;
        held = false;
      } else {
        held = m_->out_valid;
        if (held) held_tok = port_.token();
      }
      if (m_->cfg_valid && m_->cfg_ready) ++cfg_sent;
      if (m_->in_valid && m_->in_ready) {
        if (timing) timing->in_cycle.push_back(port_.cycle);
        ++x_sent;
      }
      if (s && cfg_sent == s->freqs.size() && x_sent == s->xs.size()) {
        ++seg;
        cfg_sent = x_sent = 0;
        base_ += s->xs.size() * s->freqs.size();
      }
      port_.tick_high();
    }
  }

 private:
  size_t expected_before(const std::vector<Segment>&, size_t) const { return base_; }
  sdft_port::SdftPort<V, ACC_W> port_;
  V* const m_ = port_.m.get();
  Bank bank_;
  size_t base_ = 0;  // tokens of the segments already fully sent
};

const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};
const std::vector<double> kOdd = {800, 2500, 6000, 11000, 16500};

std::vector<int32_t> scene_samples() {
  const auto scene = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  eskin::sim::WorldModel world(scene);
  const int mid = int(std::lround(scene.skin.adc.mid_code()));
  std::vector<int32_t> xs;
  for (int c : world.all_codes()) xs.push_back(c - mid);
  return xs;
}

using Default = Harness<Vsdft_bank, SdftBank<6, 32>, 13, 24>;
using Odd = Harness<Vsdft_bank_odd, SdftBank<8, 48, 12, 12, 8, 21, 2>, 12, 21>;

TEST(SdftBankRtl, RandomWithBackPressure) {
  auto h = std::make_unique<Default>();
  h->run({{kThesis, random_samples(13, 100000, 1)}}, 0.7, 0.6, 11);
}

TEST(SdftBankRtl, DefaultSceneAndReconfigure) {
  auto h = std::make_unique<Default>();
  const auto xs = scene_samples();
  ASSERT_GT(xs.size(), 10000u);
  // Scene, then a reconfiguration to 3 carriers (clears state), then the
  // scene's carriers again with pinned extremes.
  std::vector<int32_t> extremes(3000);
  for (size_t i = 0; i < extremes.size(); ++i)
    extremes[i] = i < 1000 ? 4095 : i < 2000 ? -4096 : (i % 2 ? 4095 : -4096);
  h->run({{kThesis, xs}, {{2000, 6000, 12000}, random_samples(13, 5000, 2)}, {kThesis, extremes}},
         0.5, 0.5, 12);
}

TEST(SdftBankRtl, OddParametersWithBackPressure) {
  auto h = std::make_unique<Odd>();
  h->run({{kOdd, random_samples(12, 100000, 3)}, {{1000, 9000}, random_samples(12, 3000, 4)}},
         0.8, 0.7, 13);
}

// Exact cycle counts with in_valid and out_ready always high.
template <class H>
void check_timing(const std::vector<double>& freqs, int xw) {
  auto h = std::make_unique<H>();
  Timing t;
  h->run({{freqs, random_samples(xw, 200, 5)}}, 1.0, 1.0, 14, &t);
  const uint64_t k = freqs.size(), ii = 6 * k + 2, latency = 8;
  ASSERT_EQ(t.in_cycle.size(), 200u);
  ASSERT_EQ(t.out_cycle.size(), 200u * k);
  for (size_t s = 0; s < t.in_cycle.size(); ++s) {
    if (s > 0) {
      EXPECT_EQ(t.in_cycle[s] - t.in_cycle[s - 1], ii) << "sample " << s;
    }
    for (uint64_t j = 0; j < k; ++j) {
      EXPECT_EQ(t.out_cycle[s * k + j] - t.in_cycle[s], latency + 6 * j)
          << "sample " << s << " token " << j;
    }
  }
}

TEST(SdftBankRtl, LatencyAndInitiationInterval) {
  check_timing<Default>(kThesis, 13);
  check_timing<Odd>(kOdd, 12);
}

// One carrier (K = 1), the tightest case of the pipelined schedule: carrier
// 0's phase and sums are written back in C6 and read again in the very next
// clock (IDLE, the next handshake at full rate), where its first sine lookup
// is issued in OLD from that read. Bound: bit-exact tokens (the read after
// write must see the new values) and, at full rate, exactly II = 6 K + 2 = 8
// and latency 8; then with gaps and back-pressure (stalls in C6 repeat the
// next carrier's lookup), and after a reconfiguration from 6 carriers to 1.
TEST(SdftBankRtl, OneCarrierBackToBack) {
  check_timing<Default>({3000}, 13);
  check_timing<Odd>({9000}, 12);
  auto h = std::make_unique<Default>();
  h->run({{kThesis, random_samples(13, 3000, 6)}, {{3000}, random_samples(13, 20000, 7)}}, 0.9,
         0.6, 15);
}

}  // namespace
