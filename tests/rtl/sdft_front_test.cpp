// rtl/sdft_front.v (a sample FIFO in front of rtl/sdft_lanes.v) into
// rtl/frame_capture.v (tests/rtl/sdft_front_tb.v), fed by a model of
// rtl/adc_ad7476.v's output: a conversion every P clocks, visible from its
// clock, held until taken; a conversion that finds the previous one still
// held is dropped (the ADC's `overruns`), its t counted all the same. The
// frame engine's side reads each frame as soon as it is pending.
// Bounds, all exact (rtl/sdft_front.v's header):
//  * pace: sample j (arriving at a_j) enters the lanes at
//      h_j = max(a_j, h_{j-1} + I_{j-1}),
//    I = F = sdft_lanes_interval(K, L, 1) after a frame's sample, S =
//    sdft_skip_interval(K, L) after any other, clock for clock;
//  * backlog: the FIFO holds at most min(DEPTH, floor((F - 1) / P))
//    samples (hls::sdft_front_backlog), and the longest wait of a sample
//    between its conversion and the lanes is F - P (the sample after a
//    frame's);
//  * loss: none when P >= hls::sdft_front_min_period(F, S, STEP, DEPTH);
//    at the period one clock shorter a sample is lost (each of its three
//    conditions met at its edge by one build or period below);
//  * frames: every sample the frame rule picks (tests/rtl/frame_rule.h)
//    becomes a frame whose 2 K words are that sample's tokens from the HLS
//    kernel (hls/sdft_bank.h), with the sample's ADC t, none lost.
// Builds (sdft_front_test.cmake): default, a 64x64 skin's DFT at 1 MS/s
// (KS 128, N 512, 32 lanes, FIFO 4, STEP 1000); d0, no FIFO (KS 64, N
// 128, 16 lanes: the ADC's register alone, as rtl/dtmf_top.v is wired).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <vector>

#include "Vsdft_front_tb.h"
#include "Vsdft_front_tb_d0.h"
#include "dft_capture_bench.h"
#include "frame_rule.h"
#include "hls/sdft_bank.h"
#include "sdft_port.h"

namespace {

template <class V, int KS, int N, int ACC_W, int LANES, int DEPTH, int STEP>
struct Build {
  using Model = V;
  using Bank = eskin::hls::SdftBank<KS, N, 12, 16, 10, ACC_W>;
  static constexpr int kKs = KS, kN = N, kLanes = LANES, kDepth = DEPTH, kStep = STEP;
  static int64_t f() { return eskin::hls::sdft_lanes_interval(KS, LANES, 1); }
  static int64_t s() { return eskin::hls::sdft_skip_interval(KS, LANES); }
  static int64_t min_period() { return eskin::hls::sdft_front_min_period(f(), s(), STEP, DEPTH); }
};
using F4 = Build<Vsdft_front_tb, 128, 512, 22, 32, 4, 1000>;
using D0 = Build<Vsdft_front_tb_d0, 64, 128, 20, 16, 0, 1000>;

struct Result {
  size_t adc_lost = 0, taken = 0, frames_want = 0, frames_read = 0, tokens = 0;
  size_t tokens_refused = 0, pace_errors = 0;
  uint32_t overruns = 0;
  int max_backlog = 0;
  uint64_t max_wait = 0;
};

// All KS channels with random increments, then `conversions` random
// samples at one every `period` clocks.
template <class B>
void run(size_t conversions, uint64_t period, uint64_t seed, Result& r) {
  constexpr int k = B::kKs;
  dft_capture_bench::Bench<typename B::Model> bench;
  auto& m = bench.m;
  const uint64_t& cycle = bench.cycle;
  m->s_valid = 0;
  bench.reset();
  auto bank = bench.template configure<typename B::Bank>(k, seed);
  ASSERT_TRUE(bank) << "the kernel refuses the carriers";
  eskin::hls::SdftBankToken toks[k];

  const auto xs = sdft_port::random_samples(12, conversions, seed + 1);
  frame_rule::FrameRule rule(B::kN, B::kStep);
  struct Sample {
    size_t j;      // conversion index: the ADC's t
    uint64_t at;   // its conversion's clock
  };
  std::deque<Sample> queued;  // taken from the ADC, not yet in the lanes (FIFO order)
  dft_capture_bench::FrameReader reader;
  reader.k = k;
  bool held = false;
  Sample adc{};
  size_t conv = 0;
  uint64_t last_entry = 0, last_interval = 0;
  bool first = true;
  const uint64_t start = cycle;
  uint64_t progress = cycle;
  for (uint64_t end = ~uint64_t(0); cycle < end;) {
    ASSERT_LT(cycle - progress, 20000u) << "stalled at conversion " << conv;
    if (conv < conversions && cycle == start + conv * period) {  // a conversion completes
      if (held) {
        ++r.adc_lost;  // the previous one was not taken: this one is dropped
      } else {
        held = true;
        adc = {conv, cycle};
      }
      ++conv;
      progress = cycle;
      if (conv == conversions) end = cycle + 20 * period + 400 + 2 * uint64_t(k);
    }
    m->s_valid = held;
    m->s_x = uint16_t(xs[adc.j] & 0xFFF);
    m->s_t = uint32_t(adc.j);
    ASSERT_TRUE(reader.before_edge(*m));
    m->clk = 0;
    m->eval();
    r.max_backlog = std::max(r.max_backlog, int(m->backlog));
    r.tokens_refused += m->tok_valid && !m->tok_ready;
    r.tokens += m->tok_valid && m->tok_ready;
    if (m->s_valid && m->s_ready) {
      queued.push_back(adc);
      held = false;
    }
    if (m->dft_fire) {
      ASSERT_FALSE(queued.empty()) << "a sample entered the lanes that the ADC did not give";
      const Sample smp = queued.front();
      queued.pop_front();
      // h_j = max(a_j, h_{j-1} + I_{j-1}), clock for clock.
      const uint64_t due = first ? smp.at : std::max(smp.at, last_entry + last_interval);
      if (cycle != due && r.pace_errors++ < 5)
        ADD_FAILURE() << "sample " << smp.j << " entered the lanes at " << cycle - start
                      << ", expected " << due - start;
      r.max_wait = std::max(r.max_wait, cycle - smp.at);
      ASSERT_EQ(bank->push(xs[smp.j], toks), k);
      const bool frame = rule.next();
      if (frame) reader.expect(uint32_t(smp.j), toks);
      first = false;
      last_entry = cycle;
      last_interval = uint64_t(frame ? B::f() : B::s());
      ++r.taken;
      progress = cycle;
    }
    bench.tick();
    reader.after_edge(*m);
  }
  EXPECT_TRUE(queued.empty() && !held) << "samples left behind";
  r.frames_want = reader.wanted;
  r.frames_read = reader.read;
  r.overruns = m->overruns;
}

// Three frames (samples N - 1 + STEP j, j = 0..2).
template <class B>
size_t three_frames() {
  return size_t(B::kN) + 2 * size_t(B::kStep) + 1;
}

template <class B>
void expect_keeps_up(uint64_t period, uint64_t seed) {
  const int k = B::kKs;
  Result r;
  const size_t n = three_frames<B>();
  run<B>(n, period, seed, r);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(r.adc_lost, 0u) << "P " << period;
  EXPECT_EQ(r.taken, n);
  EXPECT_EQ(r.pace_errors, 0u);
  EXPECT_EQ(r.max_backlog,
            std::min<int64_t>(B::kDepth, eskin::hls::sdft_front_backlog(B::f(), int64_t(period))))
      << "P " << period;
  EXPECT_EQ(r.max_wait, uint64_t(B::f()) - period) << "P " << period;
  EXPECT_EQ(r.frames_want, 3u);
  EXPECT_EQ(r.frames_read, 3u);
  EXPECT_EQ(r.tokens, 3u * size_t(k));
  EXPECT_EQ(r.tokens_refused, 0u);
  EXPECT_EQ(r.overruns, 0u);
}

template <class B>
void expect_loses(uint64_t period, uint64_t seed) {
  Result r;
  run<B>(three_frames<B>(), period, seed, r);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_GT(r.adc_lost, 0u) << "P " << period << ": no sample lost one clock below the bound";
}

// A 64x64 skin (128 bin-centred carriers, no DC channel) at 1 MS/s: F = 128
// + 8 = 136, S = 6 ceil(128 / 32) + 2 = 26. At 40 MHz (P = 40) the FIFO
// holds floor(135 / 40) = 3 samples after a frame's and the next sample
// waits 96 clocks; at 50 MHz 2 samples, 86 clocks.
TEST(SdftFront, SixtyFourBySixtyFourAtOneMegasampleAt40And50MHzLosesNoSample) {
  ASSERT_EQ(F4::f(), 136);
  ASSERT_EQ(F4::s(), 26);
  ASSERT_EQ(eskin::hls::sdft_front_backlog(136, 40), 3);
  ASSERT_EQ(eskin::hls::sdft_front_backlog(136, 50), 2);
  expect_keeps_up<F4>(40, 1);
  expect_keeps_up<F4>(50, 2);
}

// The least period with a FIFO of 4: set by the catch-up, STEP P >= F +
// (STEP - 1) S: 27 (1000 x 26 = 26000 < 136 + 999 x 26 = 26110). At 27
// the FIFO fills (floor(135 / 27) = 5 samples wait: 4 in the FIFO, one in
// the ADC's register) and nothing is lost; at 26 = S the delay after a
// frame never shrinks, the next frame's adds to it, and a sample is lost.
TEST(SdftFront, FourSampleFifoAtItsLeastPeriodAndOneClockBelow) {
  ASSERT_EQ(F4::min_period(), 27);
  expect_keeps_up<F4>(27, 3);
  expect_loses<F4>(26, 4);
}

// Without a FIFO (the ADC's register alone): the sample after a frame's
// must be taken before the next conversion, F < 2 P. 64 channels in 16
// lanes: F = 72, S = 26, least period 37; at 36 (F = 2 P) the sample
// after the frame's is taken in the clock the next conversion lands, one
// too late, and that conversion is lost.
TEST(SdftFront, NoFifoNeedsTheFrameSampleShorterThanTwoPeriods) {
  ASSERT_EQ(D0::f(), 72);
  ASSERT_EQ(D0::s(), 26);
  ASSERT_EQ(D0::min_period(), 37);
  expect_keeps_up<D0>(37, 5);
  expect_loses<D0>(36, 6);
}

// The formulas at other sets, against their statement: a FIFO of D holds
// off the loss while F < (D + 2) P.
TEST(SdftFront, LeastPeriodFormula) {
  using eskin::hls::sdft_front_min_period;
  EXPECT_EQ(sdft_front_min_period(136, 26, 1000, 0), 69);  // F < 2 P
  EXPECT_EQ(sdft_front_min_period(136, 26, 1000, 1), 46);  // F < 3 P
  EXPECT_EQ(sdft_front_min_period(136, 26, 1000, 2), 35);  // F < 4 P
  EXPECT_EQ(sdft_front_min_period(136, 14, 1000, 4), 23);  // F < 6 P (64 lanes: S = 14)
  EXPECT_EQ(sdft_front_min_period(136, 14, 1, 4), 136);    // every sample a frame's
  EXPECT_EQ(sdft_front_min_period(136, 50, 1000, 4), 51);  // 16 lanes: S = 50, catch-up
}

}  // namespace
