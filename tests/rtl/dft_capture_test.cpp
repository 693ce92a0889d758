// rtl/sdft_lanes.v into rtl/frame_capture.v as rtl/dtmf_top.v wires them
// (tests/rtl/dft_capture_tb.v), a sample offered every clock, for every
// K = 1..KS of the build, the frame engine's side reading each frame as
// soon as it is pending. Bounds, all exact:
//  * pace: the capture takes every token in the clock it is offered
//    (tok_ready high whenever tok_valid), so the merger runs at G = 1 and
//    samples are taken every
//      II = 6 K + 2 with 1 lane (sdft_bank: the next handshake comes in
//           the clock of the last token),
//      II = 9 + (K - 1) + max(0, 6 - L) (ceil(K / L) - 1) with L >= 2
//           (the next handshake in the clock of the last token too)
//    clocks after a frame's sample (rtl/sdft_lanes.v's header, coded here
//    from its statement with G = 1), and II_skip = 6 ceil(K / L) + 2 after
//    any other, whose tokens the top skips (frame_capture's smp_frame);
//    those are the budget's hls::dtmf_top_sdft_clocks(K, L) and
//    dtmf_top_sdft_skip_clocks(K, L), so the budget asks the RTL's own
//    pace, not a clock more or less; only the frames' tokens come out;
//  * frames at that pace: every sample the frame rule picks (coded from
//    hls/dtmf_chain.h, tests/rtl/frame_rule.h) becomes a frame, in order,
//    whose 2 K words are that sample's tokens from the HLS kernel
//    (hls/sdft_bank.h: re at 2k, im at 2k + 1, sign-extended), with its t,
//    and no frame is lost (overruns 0): the capture stores a token per
//    clock and judges the last one in its own clock, and the engine here
//    reads a frame in 2 K + 2 clocks, less than STEP x II.
// Builds (dft_capture_test.cmake): default 6 lanes, KS 24, N 64, ACC_W 19
// (a 12x12 skin's DFT at 1 MS/s: 24 carriers; II = K + 8 = 32 for K = 24,
// inside the 40 clocks of a 40 MHz core); l1: one lane, KS 7,
// N 32, ACC_W 18 (the default 3x3 top's DFT). STEP 3 in both. s32: the
// ADC's pace at a 32x32 skin's 1 MS/s (its test states its bounds).
// The cycle level's C++ models (sim/cycle/sdft_bank.h into
// sim/cycle/frame_capture.h) give the same ready signals, token valid and
// last, pending, frame_t, overruns and engine reads as the l1 build at
// every clock, under random samples, carrier tables (reloaded mid-stream,
// and written with samples between their writes), reads, releases and
// clears (bound: exact).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "Vdft_capture_tb.h"
#include "Vdft_capture_tb_l1.h"
#include "Vdft_capture_tb_s32.h"
#include "dft_capture_bench.h"
#include "sim/cycle/frame_capture.h"
#include "sim/cycle/sdft_bank.h"
#include "frame_rule.h"
#include "eskin/dtmf_top_plan.h"
#include "hls/sdft_bank.h"
#include "sdft_port.h"

namespace {

using eskin::hls::SdftBankToken;

template <class V, int KS, int N, int ACC_W, int LANES, int STEP = 3>
struct Build {
  using Model = V;
  using Bank = eskin::hls::SdftBank<KS, N, 12, 16, 10, ACC_W>;
  static constexpr int kKs = KS, kN = N, kAccW = ACC_W, kLanes = LANES, kStep = STEP;
};
using L6 = Build<Vdft_capture_tb, 24, 64, 19, 6>;
using L1 = Build<Vdft_capture_tb_l1, 7, 32, 18, 1>;
using S32 = Build<Vdft_capture_tb_s32, 64, 128, 20, 11, 1000>;

struct Result {
  std::vector<uint64_t> in_cycle;  // each sample's handshake
  std::vector<bool> frame;         // each sample is a frame's
  size_t frames_want = 0, frames_read = 0, tokens_refused = 0, tokens = 0;
  uint32_t overruns = 0;
  // ADC pace (period > 0): samples lost (the previous one not taken by the
  // next conversion) and the longest a sample waited for the DFT.
  size_t adc_lost = 0;
  uint64_t max_wait = 0;
};

// K channels with random increments, then `n` random samples offered every
// clock (period 0), or as adc_ad7476 offers them (period > 0: a
// conversion every `period` clocks, held until taken; one that finds the
// previous still held replaces it, a lost sample); the engine reads each
// pending frame word by word and releases it.
template <class B>
void run(int k, size_t n, uint64_t seed, Result& r, uint64_t period = 0) {
  dft_capture_bench::Bench<typename B::Model> bench;
  auto& m = bench.m;
  const uint64_t& cycle = bench.cycle;
  m->in_valid = 0;
  bench.reset();
  auto bank = bench.template configure<typename B::Bank>(k, seed);
  ASSERT_TRUE(bank) << "K " << k << ": the kernel refuses the carriers";

  const auto xs = sdft_port::random_samples(12, n, seed + 1);
  frame_rule::FrameRule rule(B::kN, B::kStep);
  dft_capture_bench::FrameReader reader;
  reader.k = k;
  reader.context = "K " + std::to_string(k) + ": ";
  SdftBankToken toks[B::kKs];
  size_t next = 0;
  const uint64_t start = cycle;
  bool held = period == 0;  // the ADC holds sample `next` (offered every clock without a pace)
  uint64_t held_since = start;
  uint64_t last_fire = cycle;
  for (uint64_t end = ~uint64_t(0); cycle < end;) {
    ASSERT_LT(cycle - last_fire, 2000u) << "K " << k << ": stalled at sample " << next;
    if (period > 0 && next < n && (cycle - start) % period == 0 &&
        (cycle - start) / period >= next) {  // a conversion completes
      if (held) ++r.adc_lost;  // the previous one was not taken
      held = true;
      held_since = cycle;
    }
    m->in_valid = next < n && held;
    m->in_x = next < n ? uint16_t(xs[next] & 0xFFF) : 0;
    ASSERT_TRUE(reader.before_edge(*m));
    m->clk = 0;
    m->eval();
    r.tokens_refused += m->tok_valid && !m->tok_ready;
    const bool in_fire = m->in_valid && m->in_ready;
    r.tokens += m->tok_valid && m->tok_ready;
    if (in_fire) {
      last_fire = cycle;
      r.in_cycle.push_back(cycle);
      r.max_wait = std::max(r.max_wait, cycle - held_since);
      held = period == 0;
      ASSERT_EQ(bank->push(xs[next], toks), k);
      r.frame.push_back(false);
      if (rule.next()) {
        r.frame.back() = true;
        reader.expect(uint32_t(next), toks);
      }
      if (++next == n) end = cycle + 400 + 2 * uint64_t(k);  // the last frame's tokens and read
    }
    bench.tick();
    reader.after_edge(*m);
  }
  r.frames_want = reader.wanted;
  r.frames_read = reader.read;
  r.overruns = m->overruns;
}

template <class B>
void check_pace_and_frames() {
  const int L = B::kLanes;
  for (int k = 1; k <= B::kKs; ++k) {
    const int wait = std::max(0, 6 - L);  // idle clocks per row boundary at G = 1
    const int64_t ii = L == 1 ? 6 * k + 2 : 9 + (k - 1) + wait * ((k + L - 1) / L - 1);
    const int64_t ii_skip = 6 * ((k + L - 1) / L) + 2;  // a sample that is no frame's
    ASSERT_EQ(ii, eskin::hls::dtmf_top_sdft_clocks(k, L)) << "K " << k << ": the budget's figure";
    ASSERT_EQ(ii_skip, eskin::hls::dtmf_top_sdft_skip_clocks(k, L)) << "K " << k;
    Result r;
    const size_t n = size_t(B::kN) + 12 * B::kStep;
    run<B>(k, n, uint64_t(100 + k), r);
    if (::testing::Test::HasFatalFailure()) return;
    ASSERT_EQ(r.in_cycle.size(), n);
    for (size_t s = 1; s < n; ++s)
      ASSERT_EQ(int64_t(r.in_cycle[s] - r.in_cycle[s - 1]), r.frame[s - 1] ? ii : ii_skip)
          << "K " << k << " sample " << s;
    EXPECT_EQ(r.tokens_refused, 0u) << "K " << k;
    EXPECT_EQ(r.frames_want, 13u) << "K " << k;  // samples N - 1 + 3 j, j = 0..12
    EXPECT_EQ(r.tokens, 13u * size_t(k)) << "K " << k << ": tokens only for the frames";
    EXPECT_EQ(r.frames_read, r.frames_want) << "K " << k;
    EXPECT_EQ(r.overruns, 0u) << "K " << k;
  }
}

TEST(DftCapture, SixLanesTakeASampleEveryKPlus9ClocksAndKeepEveryFrame) {
  check_pace_and_frames<L6>();
}

TEST(DftCapture, OneLaneTakesASampleEvery6KPlus2ClocksAndKeepsEveryFrame) {
  check_pace_and_frames<L1>();
}

// A 32x32 skin's DFT (64 carriers, N 128) at 1 MS/s on a 40 MHz core: 11
// lanes, the ADC's pace (a conversion every 40 clocks, one held). A frame's
// sample takes F = 64 + 8 = 72 clocks and every other one S = 6 ceil(64 /
// 11) + 2 = 38 (both asserted clock for clock above at smaller builds), so
// the budget's P >= S, F < 2 P and F - P <= (STEP - 1)(P - S) hold (39 <=
// 40) and no sample may be lost: the sample after a frame's waits exactly F
// - P = 32 clocks (it comes P after the frame's, which the DFT took at
// once), and each later one 2 clocks less, back to 0 long before the next
// frame. Three frames, every word equal to the kernel's.
TEST(DftCapture, ThirtyTwoByThirtyTwoAtOneMegasampleInElevenLanesLosesNoSample) {
  constexpr int k = 64;
  const uint64_t period = 40;
  ASSERT_EQ(eskin::hls::dtmf_top_sdft_clocks(k, S32::kLanes), 72);
  ASSERT_EQ(eskin::hls::dtmf_top_sdft_skip_clocks(k, S32::kLanes), 38);
  ASSERT_LE(eskin::hls::dtmf_top_sdft_min_period(k, S32::kLanes, S32::kStep), long(period));
  ASSERT_GT(eskin::hls::dtmf_top_sdft_min_period(k, S32::kLanes - 1, S32::kStep), long(period))
      << "10 lanes would do";
  Result r;
  const size_t n = size_t(S32::kN) + 2 * S32::kStep + 1;  // frames at N - 1 + 1000 j, j = 0..2
  run<S32>(k, n, 7, r, period);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(r.adc_lost, 0u);
  EXPECT_EQ(r.max_wait, 72u - period);
  ASSERT_EQ(r.in_cycle.size(), n);
  EXPECT_EQ(r.frames_want, 3u);
  EXPECT_EQ(r.frames_read, 3u);
  EXPECT_EQ(r.tokens, 3u * k);
  EXPECT_EQ(r.tokens_refused, 0u);
  EXPECT_EQ(r.overruns, 0u);
}

// The l1 build against the cycle models, clock by clock. Random traffic:
// samples offered 70 % of clocks, carrier tables of 1..7 carriers written
// now and then (every few thousand clocks, with gaps between their writes
// in which samples go in), the engine's read address random below 2 KS,
// releases and counter clears at random.
TEST(DftCapture, CycleModelsEqualTheRtlEveryClock) {
  dft_capture_bench::Bench<Vdft_capture_tb_l1> b;
  auto& m = *b.m;
  m.in_valid = 0;
  b.reset();
  eskin::cycle::SdftBank sdft(7, 32, 18);
  eskin::cycle::FrameCapture cap(7, 18, 32, 3);
  sdft.reset();
  cap.reset();
  std::mt19937_64 rng(77);
  uint32_t t = 0;
  int cfg_left = 0, cfg_k = 0, cfg_n = 0;  // a table being written: carriers left, next, its K
  long frames = 0, tokens = 0, compared_reads = 0;
  bool both_banks = false;
  for (long c = 0; c < 400000; ++c) {
    // A new carrier table now and then, first at once.
    if (cfg_left == 0 && (c == 0 || rng() % 6000 == 0)) {
      cfg_n = 1 + int(rng() % 7);
      if (c == 0) cfg_n = 7;  // both banks hold every word before reads count
      cfg_left = cfg_n, cfg_k = 0;
    }
    const bool cfg_valid = cfg_left > 0 && rng() % 4 == 0;
    const bool cfg_last = cfg_left == 1;
    const uint32_t cfg_inc = uint32_t(rng());
    const bool in_valid = rng() % 10 < 7;
    const int32_t x = int32_t(rng() % 4096) - 2048;
    const uint8_t rd_addr = uint8_t(rng() % 14);
    const bool done = rng() % 40 == 0;
    const bool clear = rng() % 5000 == 0;
    m.cfg_valid = cfg_valid;
    m.cfg_k = uint8_t(cfg_k);
    m.cfg_inc = cfg_inc;
    m.cfg_last = cfg_last;
    m.in_valid = in_valid;
    m.in_x = uint16_t(x & 0xFFF);
    m.rd_addr = rd_addr;
    m.done = done;
    m.clear = clear;
    m.clk = 0;
    m.eval();
    const bool ir = sdft.in_ready(cfg_valid);
    ASSERT_EQ(bool(m.in_ready), ir) << "clock " << c;
    ASSERT_EQ(bool(m.cfg_ready), sdft.cfg_ready()) << "clock " << c;
    ASSERT_EQ(bool(m.tok_valid), sdft.out_valid()) << "clock " << c;
    if (sdft.out_valid()) {
      ASSERT_EQ(bool(m.tok_last), sdft.out_last()) << "clock " << c;
    }
    ASSERT_EQ(bool(m.pending), cap.pending()) << "clock " << c;
    ASSERT_EQ(m.frame_t, cap.frame_t()) << "clock " << c;
    ASSERT_EQ(m.overruns, cap.overruns()) << "clock " << c;
    if (both_banks) {
      ASSERT_EQ(m.rd_data, cap.rd_data()) << "clock " << c;
      ++compared_reads;
    }
    const bool fire = in_valid && ir;
    const bool skip = !cap.smp_frame();  // from the capture's registers before the edge
    const bool cfg_fire = cfg_valid && sdft.cfg_ready();
    tokens += sdft.out_valid();
    frames += done && cap.pending();
    if (frames >= 2 && cap.pending()) both_banks = true;
    cap.clock(cfg_fire && cfg_last, fire, t, sdft.out_valid(), sdft.out_last(), sdft.out_re(),
              sdft.out_im(), rd_addr, done, clear);
    sdft.clock(in_valid, x, skip, cfg_valid, uint8_t(cfg_k), cfg_inc, cfg_last,
               true);
    if (fire) ++t;
    if (cfg_fire) --cfg_left, ++cfg_k;
    b.tick();
  }
  EXPECT_GT(frames, 1000);
  EXPECT_GT(tokens, 7000);
  EXPECT_GT(compared_reads, 300000);
}

}  // namespace
