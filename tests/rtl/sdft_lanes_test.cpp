// rtl/sdft_lanes.v against hls/sdft_bank.h, token by token.
//
// Bound: bit-exact ({k, re, im, last} equal for every token, in order):
// the lanes split the channels, and each channel's arithmetic is
// sdft_bank's, whose executable spec is the HLS kernel; the kernel here
// holds all K channels in one bank, so the test checks the splitting, the
// configuration routing and the merge as well. Checked with random gaps on
// in_valid and cfg_valid, random back-pressure on out_ready, random
// increments (any 32-bit value), random full-scale samples, configurations
// written in random order with rewritten entries, and reconfigurations
// (more and fewer channels than lanes); plus the stream rules (a token
// offered and not taken stays unchanged; no token lost, duplicated,
// reordered or extra) and, for LANES >= 2, that every token of a sample
// was taken by the next sample's handshake, the last one at the latest in
// that clock (rtl/frame_capture.v stores and judges it in its clock).
// Skipped samples (in_skip): they move the state as any sample (the model
// is pushed every sample) and give no token; the random runs skip about 2
// in 3 samples in every other configuration.
// Timing (header of rtl/sdft_lanes.v): with in_valid always high, the
// consumer taking every token offered and then needing G clocks (1: out_ready
// always high, as rtl/frame_capture.v keeps it; 2: a consumer that stores a
// token in two clocks), token k of a sample is taken
//   9 + G k + max(0, 6 - G LANES) floor(k / LANES)
// clocks after the sample's handshake, and samples are accepted every
//   II = 9 + G (K - 1) + max(0, 6 - G LANES) (ceil(K / LANES) - 1)
// clocks (the next sample in the clock the last token is taken); LANES 1 is
// sdft_bank: 8 + 6 k and 6 K + 2. After a skipped sample the next comes
// 6 ceil(K / LANES) + 2 clocks later. Asserted exactly.
// Builds (sdft_lanes_test.cmake): LANES 2 (K_MAX 9, N 32, XW 12, ACC_W 18:
// a 4x4 skin's DFT in dtmf_top), 3 (K_MAX 13, N 48, XW 12, CW 12, TW 8,
// FB 2, ACC_W 21), 8 (K_MAX 20, N 64, ACC_W 20: the merger's regime
// G LANES >= 6 for both consumers), 32 (K_MAX 128, N 512, XW 12, ACC_W 22:
// a 64x64 skin's 128 bin-centred carriers at 1 MS/s, the top's pattern of
// one sample in STEP with tokens) and 1 (sdft_bank's defaults).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "Vsdft_lanes.h"
#include "Vsdft_lanes_l1.h"
#include "Vsdft_lanes_l3.h"
#include "Vsdft_lanes_l32.h"
#include "Vsdft_lanes_l8.h"
#include "hls/sdft_bank.h"
#include "sdft_port.h"

namespace {

using eskin::hls::SdftBankToken;

using sdft_port::random_samples;

struct CfgWrite {
  int k;
  uint32_t inc;
  bool last;
};

// A configuration (the writes as the port sees them; the kernel gets `inc`)
// and the samples after it.
struct Segment {
  std::vector<uint32_t> inc;
  std::vector<CfgWrite> writes;
  std::vector<int32_t> xs;
  std::vector<bool> skip;  // per sample: in_skip (no tokens); empty: none skipped
  bool skipped(size_t i) const { return i < skip.size() && skip[i]; }
};

enum class Consumer { Random, Always, TwoClock };

struct Timing {
  std::vector<uint64_t> in_cycle, out_cycle;
};

// K random increments written in random order, some entries first written
// with a wrong value and rewritten later; k = K - 1 last, with cfg_last.
Segment segment(int k, std::vector<int32_t> xs, uint64_t seed, bool shuffle) {
  std::mt19937_64 rng(seed);
  Segment s;
  s.xs = std::move(xs);
  for (int i = 0; i < k; ++i) s.inc.push_back(uint32_t(rng()));
  for (int i = 0; i + 1 < k; ++i) s.writes.push_back({i, s.inc[size_t(i)], false});
  if (shuffle) {
    std::shuffle(s.writes.begin(), s.writes.end(), rng);
    for (int r = 0; r < k / 2; ++r) {  // a wrong value first, the right one later
      const int i = int(rng() % uint64_t(k));
      s.writes.insert(s.writes.begin(), {i, uint32_t(rng()), false});
      if (i == k - 1) continue;
      const size_t at = 1 + size_t(rng() % s.writes.size());
      s.writes.insert(s.writes.begin() + long(at), {i, s.inc[size_t(i)], false});
    }
  }
  s.writes.push_back({k - 1, s.inc[size_t(k - 1)], true});
  return s;
}

std::vector<int32_t> extremes(int xw, size_t n) {
  std::vector<int32_t> xs(n);
  const int32_t hi = (1 << (xw - 1)) - 1, lo = -(1 << (xw - 1));
  for (size_t i = 0; i < n; ++i) xs[i] = i < n / 3 ? hi : i < 2 * n / 3 ? lo : (i % 2 ? hi : lo);
  return xs;
}

template <class V, class Bank, int LANES, int XW, int ACC_W>
class Harness {
 public:
  static constexpr int kLanes = LANES, kXw = XW;

  // Drives the segments in order: each one's configuration writes, then its
  // samples (the next configuration is offered as soon as the last sample
  // was taken: the module must hold it until the tokens are out).
  void run(const std::vector<Segment>& segs, double p_valid, Consumer consumer, double p_ready,
           uint64_t seed, Timing* timing = nullptr) {
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution offer(p_valid), ready(p_ready);
    std::vector<SdftBankToken> expect;
    std::vector<size_t> before;  // tokens expected before each sample, in input order
    for (const Segment& s : segs) {
      typename Bank::Config cfg;
      cfg.carriers = int(s.inc.size());
      for (size_t i = 0; i < s.inc.size(); ++i) cfg.inc[i] = s.inc[i];
      ASSERT_TRUE(bank_.configure(cfg));
      SdftBankToken out[sizeof(cfg.inc) / sizeof(cfg.inc[0])];
      for (size_t i = 0; i < s.xs.size(); ++i) {
        before.push_back(expect.size());
        const int n = bank_.push(s.xs[i], out);  // a skipped sample moves the state too
        if (!s.skipped(i)) expect.insert(expect.end(), out, out + n);
      }
    }
    size_t got = 0, seg = 0, w = 0, xi = 0, samples = 0;
    bool held = false, took = false;
    SdftBankToken held_tok{};
    const uint64_t limit = port_.cycle + 64 * (expect.size() + 1000) + 200 * samples_of(segs);
    while (got < expect.size() || seg < segs.size()) {
      ASSERT_LT(port_.cycle, limit) << "stalled: " << got << " of " << expect.size() << " tokens";
      const Segment* s = seg < segs.size() ? &segs[seg] : nullptr;
      const bool cfg_phase = s && w < s->writes.size();
      m_->cfg_valid = cfg_phase && offer(rng);
      if (cfg_phase) {
        m_->cfg_k = uint32_t(s->writes[w].k);
        m_->cfg_inc = s->writes[w].inc;
        m_->cfg_last = s->writes[w].last;
      }
      const bool x_phase = s && !cfg_phase && xi < s->xs.size();
      m_->in_valid = x_phase && offer(rng);
      if (x_phase) m_->in_x = uint32_t(s->xs[xi]) & ((1u << XW) - 1);
      m_->in_skip = x_phase && s->skipped(xi);
      m_->out_ready = consumer == Consumer::Always     ? 1
                      : consumer == Consumer::TwoClock ? !took
                                                       : ready(rng);
      m_->clk = 0;
      m_->eval();
      if (held) {  // a token offered and not taken is offered again unchanged
        ASSERT_TRUE(m_->out_valid) << "out_valid dropped before the handshake";
        const SdftBankToken t = port_.token();
        ASSERT_EQ(t.k, held_tok.k);
        ASSERT_EQ(t.re, held_tok.re);
        ASSERT_EQ(t.im, held_tok.im);
        ASSERT_EQ(t.last, held_tok.last);
      }
      took = m_->out_valid && m_->out_ready;
      if (m_->in_valid && m_->in_ready && LANES > 1) {  // the last may leave in this clock
        ASSERT_EQ(got + (took ? 1 : 0), before[samples])
            << "sample " << samples << " taken before the previous sample's tokens were out";
      }
      if (took) {
        const SdftBankToken t = port_.token(), &e = expect[got];
        ASSERT_EQ(t.k, e.k) << "token " << got;
        ASSERT_EQ(t.re, e.re) << "token " << got << " k " << int(e.k);
        ASSERT_EQ(t.im, e.im) << "token " << got << " k " << int(e.k);
        ASSERT_EQ(t.last, e.last) << "token " << got << " k " << int(e.k);
        if (timing) timing->out_cycle.push_back(port_.cycle);
        ++got;
        held = false;
      } else {
        held = m_->out_valid;
        if (held) held_tok = port_.token();
      }
      if (m_->cfg_valid && m_->cfg_ready) ++w;
      if (m_->in_valid && m_->in_ready) {
        if (timing) timing->in_cycle.push_back(port_.cycle);
        ++xi;
        ++samples;
      }
      if (s && w == s->writes.size() && xi == s->xs.size()) {
        ++seg;
        w = xi = 0;
      }
      port_.tick_high();
    }
    // Nothing more comes out.
    m_->in_valid = m_->cfg_valid = 0;
    m_->out_ready = 1;
    for (int i = 0; i < 300; ++i) {
      m_->clk = 0;
      m_->eval();
      ASSERT_FALSE(m_->out_valid) << "an extra token " << i << " clocks after the last";
      port_.tick_high();
    }
  }

 private:
  static size_t samples_of(const std::vector<Segment>& segs) {
    size_t n = 0;
    for (const auto& s : segs) n += s.xs.size() + s.writes.size();
    return n;
  }
  sdft_port::SdftPort<V, ACC_W> port_;
  V* const m_ = port_.m.get();
  Bank bank_;
};

using eskin::hls::SdftBank;
using L2 = Harness<Vsdft_lanes, SdftBank<9, 32, 12, 16, 10, 18>, 2, 12, 18>;
using L3 = Harness<Vsdft_lanes_l3, SdftBank<13, 48, 12, 12, 8, 21, 2>, 3, 12, 21>;
using L8 = Harness<Vsdft_lanes_l8, SdftBank<20, 64, 13, 16, 10, 20>, 8, 13, 20>;
using L1 = Harness<Vsdft_lanes_l1, SdftBank<6, 32>, 1, 13, 24>;
using L32 = Harness<Vsdft_lanes_l32, SdftBank<128, 512, 12, 16, 10, 22>, 32, 12, 22>;

// Random data, random stalls everywhere, reconfigurations between.
template <class H>
void random_run(const std::vector<int>& ks, size_t samples, uint64_t seed) {
  auto h = std::make_unique<H>();
  std::vector<Segment> segs;
  for (size_t i = 0; i < ks.size(); ++i) {
    const uint64_t sd = seed * 100 + i;
    auto xs = i % 3 == 2 ? extremes(H::kXw, samples / 4) : random_samples(H::kXw, samples, sd);
    segs.push_back(segment(ks[i], std::move(xs), sd, i > 0));
    if (i % 2 == 1) {  // every other configuration: random samples skipped
      std::mt19937_64 rng(sd + 7);
      for (size_t j = 0; j < segs.back().xs.size(); ++j) segs.back().skip.push_back(rng() % 3 != 0);
    }
  }
  h->run(segs, 0.7, Consumer::Random, 0.6, seed);
}

TEST(SdftLanesRtl, TwoLanesRandomWithReconfiguration) {
  random_run<L2>({9, 4, 9, 1, 7, 2}, 20000, 1);
}

TEST(SdftLanesRtl, ThreeLanesOddWidthsRandomWithReconfiguration) {
  random_run<L3>({13, 5, 13, 2, 11, 3}, 20000, 2);
}

TEST(SdftLanesRtl, EightLanesFewerChannelsThanLanes) {
  random_run<L8>({5, 20, 1, 17, 7, 20}, 10000, 3);
}

TEST(SdftLanesRtl, OneLaneIsSdftBank) {
  random_run<L1>({6, 3, 6, 1}, 20000, 4);
}

// 128 channels in 32 lanes, N 512 (the window wraps: 1500 samples), then 40
// (fewer than two a lane), 128 again with full-scale extremes, and 31
// (fewer channels than lanes).
TEST(SdftLanesRtl, ThirtyTwoLanes128ChannelsRandomWithReconfiguration) {
  random_run<L32>({128, 40, 128, 31}, 1500, 5);
}

// Exact clocks with in_valid always high, for every K of the build; with
// `skips`, samples skipped in the pattern dtmf_top gives (runs of skipped
// samples between ones with tokens, here 2 in 3 skipped, and a run of 7):
// after a skipped sample the next comes II_skip = 6 ceil(K / L) + 2 clocks
// later, whatever the consumer; a sample with tokens is followed II later,
// its tokens at the same offsets as without skips.
// `step` > 3: one sample in `step` with tokens, the others skipped (dtmf_top's
// pattern with STEP samples a frame).
template <class H>
void check_timing(int k, Consumer consumer, uint64_t seed, bool skips, size_t step = 3) {
  auto h = std::make_unique<H>();
  Timing t;
  const size_t n = 60;
  Segment seg = segment(k, random_samples(H::kXw, n, seed), seed, false);
  for (size_t s = 0; s < n && skips; ++s)
    seg.skip.push_back(s % step != step - 1 || (step == 3 && s >= 30 && s < 37));
  h->run({seg}, 1.0, consumer, 1.0, seed, &t);
  const int64_t L = H::kLanes, g = consumer == Consumer::TwoClock ? 2 : 1;
  const int64_t wait = std::max<int64_t>(0, 6 - g * L);  // idle clocks per row boundary
  const int64_t ii = L == 1 ? 6 * k + 2 : 9 + g * (k - 1) + wait * ((k + L - 1) / L - 1);
  const int64_t ii_skip = 6 * ((k + L - 1) / L) + 2;     // the fullest lane's sample
  ASSERT_EQ(ii, eskin::hls::sdft_lanes_interval(k, L, g)) << "the planner's formula";
  ASSERT_EQ(ii_skip, eskin::hls::sdft_skip_interval(k, L)) << "the planner's formula";
  ASSERT_EQ(t.in_cycle.size(), n);
  size_t tok = 0;
  for (size_t s = 0; s < n; ++s) {
    if (s > 0) {
      ASSERT_EQ(int64_t(t.in_cycle[s] - t.in_cycle[s - 1]), seg.skipped(s - 1) ? ii_skip : ii)
          << "K " << k << " sample " << s << (seg.skipped(s - 1) ? " after a skipped one" : "");
    }
    if (seg.skipped(s)) continue;
    for (int64_t j = 0; j < k; ++j, ++tok) {
      const int64_t at = L == 1 ? 8 + 6 * j : 9 + g * j + wait * (j / L);
      ASSERT_LT(tok, t.out_cycle.size());
      ASSERT_EQ(int64_t(t.out_cycle[tok] - t.in_cycle[s]), at)
          << "K " << k << " G " << g << " sample " << s << " token " << j;
    }
  }
  ASSERT_EQ(tok, t.out_cycle.size()) << "tokens of skipped samples came out";
}

template <class H>
void check_timing_all(int k_max) {
  for (int k = 1; k <= k_max; ++k)
    for (bool skips : {false, true}) {
      check_timing<H>(k, Consumer::Always, uint64_t(10 + k), skips);
      check_timing<H>(k, Consumer::TwoClock, uint64_t(50 + k), skips);
    }
}

TEST(SdftLanesRtl, LatencyAndInitiationIntervalTwoLanes) { check_timing_all<L2>(9); }
TEST(SdftLanesRtl, LatencyAndInitiationIntervalThreeLanes) { check_timing_all<L3>(13); }
TEST(SdftLanesRtl, LatencyAndInitiationIntervalEightLanes) { check_timing_all<L8>(20); }
TEST(SdftLanesRtl, LatencyAndInitiationIntervalOneLane) { check_timing_all<L1>(6); }

// 32 lanes: K around the lane count and the row boundaries, up to 128; with
// no skips, the 2-in-3 pattern, and one sample in 10 with tokens.
TEST(SdftLanesRtl, LatencyAndInitiationIntervalThirtyTwoLanes) {
  for (int k : {1, 2, 31, 32, 33, 64, 65, 127, 128})
    for (Consumer c : {Consumer::Always, Consumer::TwoClock}) {
      const uint64_t seed = uint64_t(200 + k) + (c == Consumer::TwoClock ? 1000 : 0);
      check_timing<L32>(k, c, seed, false);
      check_timing<L32>(k, c, seed, true);
      check_timing<L32>(k, c, seed, true, 10);
      if (::testing::Test::HasFatalFailure()) return;
    }
}

// The figures the header quotes: a 4x4 skin's 9 channels in 2 lanes, a
// 12x12 skin's 24 and a 16x16 skin's 32 in 6 (G = 1: K + 8, the merger's
// token a clock), and the G = 2 bound 2 K + 7 from 3 lanes on.
TEST(SdftLanesRtl, QuotedIntervals) {
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(9, 1), 56);
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(9, 2), 33);
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(24, 6), 24 + 8);
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(32, 6), 40);
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(20, 8), 20 + 8);
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(9, 3, 2), 2 * 9 + 7);
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(9, 8, 2), 2 * 9 + 7);
  // Skipped samples: 24x24 (48 channels) in 8 lanes and 32x32 (64) in 11
  // take 38 clocks, inside 40; one lane is sdft_bank either way.
  EXPECT_EQ(eskin::hls::sdft_skip_interval(48, 8), 38);
  EXPECT_EQ(eskin::hls::sdft_skip_interval(64, 11), 38);
  EXPECT_EQ(eskin::hls::sdft_skip_interval(64, 10), 44);
  EXPECT_EQ(eskin::hls::sdft_skip_interval(9, 1), eskin::hls::sdft_lanes_interval(9, 1));
  // 64x64 (128 channels): the frame's sample K + 8 = 136 in any number of
  // lanes from 6 on; the others 50 in 16 lanes (no room at 50 MHz / 1 MS/s),
  // 38 in 22, 26 in 32, 14 in 64.
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(128, 16), 136);
  EXPECT_EQ(eskin::hls::sdft_lanes_interval(128, 32), 136);
  EXPECT_EQ(eskin::hls::sdft_skip_interval(128, 16), 50);
  EXPECT_EQ(eskin::hls::sdft_skip_interval(128, 22), 38);
  EXPECT_EQ(eskin::hls::sdft_skip_interval(128, 32), 26);
  EXPECT_EQ(eskin::hls::sdft_skip_interval(128, 64), 14);
}

}  // namespace
