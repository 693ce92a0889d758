// rtl/frame_capture.v between a token source shaped like sdft_bank (a
// sample handshake, then KS tokens 6 clocks apart) and a reader shaped like
// the frame engine. Bounds, all exact:
//  * frames are exactly the samples the rule of hls/dtmf_chain.h picks (the
//    N-th sample after reset or after `clr`, then every STEP-th; coded here
//    from the rule, not read from the RTL): no frame from a partly filled
//    window, also after a carrier reload in the middle of the stream;
//  * the engine's bank holds that sample's tokens (re at 2k, im at 2k + 1,
//    sign-extended) and frame_t its counter, until `done`;
//  * a frame that completes while the previous one is still pending is
//    lost and counted in `overruns` (the drop path), the pending one is
//    untouched; `clear` zeroes the count.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "Vframe_capture.h"

namespace {

constexpr int kKs = 7, kN = 32, kStep = 35, kW = 18;

struct Bench {
  std::unique_ptr<Vframe_capture> m = std::make_unique<Vframe_capture>();
  uint64_t cycle = 0;
  Bench() {
    m->clk = 0;
    m->rst = 1;
    m->clr = m->smp_fire = m->tok_valid = m->done = m->clear = 0;
    tick(), tick();
    m->rst = 0;
  }
  void tick() {
    m->clk = 0;
    m->eval();
    m->clk = 1;
    m->eval();
    ++cycle;
  }
  static int32_t token(uint32_t t, int k, int im) {  // a signed W-bit value per (t, k)
    const int32_t v = int32_t((t * 7919u + uint32_t(k) * 104729u + uint32_t(im) * 31u) % (1u << kW));
    return v - (1 << (kW - 1));
  }
  // Sample t's handshake, then its tokens 6 clocks apart, then `tail`
  // clocks. fire_next: sample t + 1's handshake comes in the clock of t's
  // last token (sdft_bank's tightest pace, 6 KS + 2 clocks a sample), and
  // that sample's tokens follow at once (call it with fired = true).
  void sample(uint32_t t, int tail = 4, bool fire_next = false, bool fired = false) {
    if (!fired) {
      m->smp_fire = 1;
      m->smp_t = t;
      tick();
      m->smp_fire = 0;
    }
    for (int k = 0; k < kKs; ++k) {
      for (int i = 0; i < 5; ++i) tick();
      m->tok_valid = 1;
      m->tok_last = k == kKs - 1;
      m->tok_re = uint32_t(token(t, k, 0)) & ((1u << kW) - 1);
      m->tok_im = uint32_t(token(t, k, 1)) & ((1u << kW) - 1);
      const bool next = fire_next && k == kKs - 1;
      m->smp_fire = next;
      m->smp_t = t + 1;
      m->eval();
      EXPECT_TRUE(m->tok_ready);
      tick();
      m->tok_valid = 0;
      m->smp_fire = 0;
    }
    for (int i = 0; i < tail; ++i) tick();
  }
  // Reads the engine's bank as the engine does (address, one clock later data).
  int32_t read(int a) {
    m->rd_addr = uint8_t(a);
    tick();
    return int32_t(m->rd_data);
  }
  template <class Sig>
  void pulse(Sig& sig) {
    sig = 1;
    tick();
    sig = 0;
  }
};

// The frame rule of hls/dtmf_chain.h, coded from its statement: the N-th
// sample after reset or a carrier reload, then every STEP-th.
struct FrameRule {
  int filled = 0, phase = 0;
  void restart() { filled = 0; }
  bool next() {  // is the next sample a frame?
    if (filled < kN) {
      phase = 0;
      return ++filled == kN;
    }
    phase = phase + 1 == kStep ? 0 : phase + 1;
    return phase == 0;
  }
};

TEST(FrameCapture, FramesFollowTheRuleAndHoldTheirTokens) {
  Bench b;
  std::mt19937 rng(4);
  FrameRule rule;
  int frames = 0, lost = 0;
  bool pending = false, hold = false;
  for (uint32_t t = 0; t < 1200; ++t) {
    if (t == 500) {  // carrier reload mid-stream: the window refills
      b.pulse(b.m->clr);
      rule.restart();
    }
    const bool frame = rule.next();
    b.sample(t);
    if (frame) {
      if (pending) {
        ++lost;
      } else {
        pending = true;
        ++frames;
        ASSERT_TRUE(b.m->pending) << "t " << t;
        ASSERT_EQ(b.m->frame_t, t);
        for (int k = 0; k < kKs; ++k) {
          ASSERT_EQ(b.read(2 * k), Bench::token(t, k, 0)) << "t " << t << " k " << k;
          ASSERT_EQ(b.read(2 * k + 1), Bench::token(t, k, 1)) << "t " << t << " k " << k;
        }
      }
    } else if (!pending) {
      ASSERT_FALSE(b.m->pending) << "a frame at t " << t;
    }
    // The engine releases most frames at once, some only after the next
    // frame has come and been lost (drop path).
    if (frame && !hold) {
      hold = rng() % 4 == 0;
      if (!hold) {
        b.pulse(b.m->done);
        pending = false;
      }
    } else if (frame && hold) {
      hold = false;
      b.pulse(b.m->done);
      pending = false;
    }
  }
  EXPECT_GT(frames, 20);
  EXPECT_GT(lost, 2);
  EXPECT_EQ(b.m->overruns, lost);
  b.pulse(b.m->clear);
  EXPECT_EQ(b.m->overruns, 0);
}

// The tightest paces: the next sample's handshake one clock after the last
// token (the DFT budget's minimum: hls::dtmf_top_sdft_clocks) must keep
// every frame and its tokens; in the clock of the last token itself
// (sdft_bank's own II, 6 KS + 2) the capture would judge that token by the
// next sample, which the budget therefore excludes (ExactPace below shows
// what goes wrong).
void run_paced(bool overlap, int& frames_ok, int& frames_wrong) {
  Bench b;
  FrameRule rule;
  frames_ok = frames_wrong = 0;
  int64_t check = -1;  // a frame sample to check once the next one's handshake is in
  for (uint32_t t = 0; t < 300; ++t) {
    const bool frame = rule.next();
    b.sample(t, 0, overlap, overlap && t > 0);
    if (check >= 0) {  // the engine reads the previous frame between samples
      const uint32_t f = uint32_t(check);
      bool good = b.m->pending && b.m->frame_t == f;
      for (int k = 0; k < kKs && good; ++k)
        good = b.read(2 * k) == Bench::token(f, k, 0) && b.read(2 * k + 1) == Bench::token(f, k, 1);
      (good ? frames_ok : frames_wrong)++;
      if (b.m->pending) b.pulse(b.m->done);
    }
    check = frame ? int64_t(t) : -1;
  }
}

TEST(FrameCapture, NextSampleOneClockAfterTheLastTokenKeepsEveryFrame) {
  int ok = 0, wrong = 0;
  run_paced(false, ok, wrong);  // handshake in the clock after the last token
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(ok, 8);  // samples 31, 66, ..., 276
}

TEST(FrameCapture, ExactPaceInTheClockOfTheLastTokenLosesFrames) {
  int ok = 0, wrong = 0;
  run_paced(true, ok, wrong);
  std::printf("handshake in the last token's clock: %d frames right, %d wrong\n", ok, wrong);
  EXPECT_GT(wrong, 0);  // why dtmf_top_sdft_clocks() asks for one clock more
}

}  // namespace
