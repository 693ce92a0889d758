// rtl/frame_capture.v between a token source shaped like sdft_bank (a
// sample handshake, then KS tokens 6 clocks apart) or like sdft_lanes from
// 6 lanes on (a token every clock) and a reader shaped like the frame
// engine. Bounds, all exact:
//  * frames are exactly the samples the rule of hls/dtmf_chain.h picks (the
//    N-th sample after reset or after `clr`, then every STEP-th; coded in
//    tests/rtl/frame_rule.h from the rule, not read from the RTL): no frame
//    from a partly filled window, also after a carrier reload in the middle
//    of the stream;
//  * the engine's bank holds that sample's tokens (re at 2k, im at 2k + 1,
//    sign-extended) and frame_t its counter, until `done`;
//  * a frame that completes while the previous one is still pending is
//    lost and counted in `overruns` (the drop path), the pending one is
//    untouched; `clear` zeroes the count;
//  * rate: tok_ready is high at every token offered, back to back (a token
//    every clock) included, with the engine reading the other bank in the
//    same clocks, and the next sample's handshake may come in the clock of
//    the previous sample's last token: every frame and word kept.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <vector>

#include "Vframe_capture.h"
#include "frame_rule.h"

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
  // Sample t's handshake, then its tokens `gap` clocks apart (6: sdft_bank;
  // 1: back to back), then `tail` clocks. fire_next: sample t + 1's
  // handshake comes in the clock of t's last token (sdft_bank's tightest
  // pace, 6 KS + 2 clocks a sample), and that sample's tokens follow at
  // once (call it with fired = true).
  void sample(uint32_t t, int tail = 4, bool fire_next = false, bool fired = false, int gap = 6) {
    if (!fired) {
      m->smp_fire = 1;
      m->smp_t = t;
      tick();
      m->smp_fire = 0;
    }
    for (int k = 0; k < kKs; ++k) {
      for (int i = 1; i < gap; ++i) tick();
      m->tok_valid = 1;
      m->tok_last = k == kKs - 1;
      m->tok_re = uint32_t(token(t, k, 0)) & ((1u << kW) - 1);
      m->tok_im = uint32_t(token(t, k, 1)) & ((1u << kW) - 1);
      const bool next = fire_next && k == kKs - 1;
      m->smp_fire = next;
      m->smp_t = t + 1;
      m->eval();
      EXPECT_TRUE(m->tok_ready) << "t " << t << " token " << k;
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

using frame_rule::FrameRule;

TEST(FrameCapture, FramesFollowTheRuleAndHoldTheirTokens) {
  Bench b;
  std::mt19937 rng(4);
  FrameRule rule(kN, kStep);
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

// sdft_bank's tightest paces (one lane): the next sample's handshake one
// clock after the last token, and in the clock of the last token itself
// (sdft_bank's own II, 6 KS + 2, which hls::dtmf_top_sdft_clocks allows):
// the last token is stored and judged in its own clock, before the new
// sample's decision takes over, so every frame keeps its tokens.
void run_paced(bool overlap, int& frames_ok, int& frames_wrong) {
  Bench b;
  FrameRule rule(kN, kStep);
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

TEST(FrameCapture, NextSampleInTheClockOfTheLastTokenKeepsEveryFrame) {
  int ok = 0, wrong = 0;
  run_paced(true, ok, wrong);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(ok, 8);
}

// A token every clock (sdft_lanes from 6 lanes on, G = 1), each sample's
// handshake in the clock of the previous sample's last token (KS clocks a
// sample), and the engine reading the pending frame a word a clock while
// the next frame's tokens go into the other bank: it starts at the
// handshake of the sample before the next frame, so its 2 KS reads and its
// `done` (2 KS + 1 clocks) end in the clock of that frame's last token,
// the swap's tightest case. Every token is taken when offered, every frame
// of the rule is handed over with its t and all 2 KS words, none is lost.
TEST(FrameCapture, TokenEveryClockWhileTheEngineReads) {
  Bench b;
  FrameRule rule(kN, kStep);
  const int64_t samples = 300;
  std::vector<bool> frame(size_t(samples) + 1);
  for (size_t i = 0; i < frame.size(); ++i) frame[i] = rule.next();
  std::deque<uint32_t> want;  // frame samples not read yet
  std::vector<int32_t> got;
  int word = -1, frames = 0;
  // Clock 0: sample 0's handshake; token j of sample s in clock 1 + KS s + j.
  const int64_t clocks = 1 + kKs * samples + 2 * kKs + 2;
  for (int64_t c = 0; c < clocks; ++c) {
    const int64_t s = c == 0 ? -1 : (c - 1) / kKs;  // the sample whose token is due
    const int j = c == 0 ? kKs - 1 : int((c - 1) % kKs);
    const bool tok = c > 0 && s < samples;
    const bool hs = j == kKs - 1 && s + 1 < samples;  // sample s + 1's handshake
    b.m->tok_valid = tok;
    b.m->tok_last = j == kKs - 1;
    b.m->tok_re = uint32_t(Bench::token(uint32_t(s), j, 0)) & ((1u << kW) - 1);
    b.m->tok_im = uint32_t(Bench::token(uint32_t(s), j, 1)) & ((1u << kW) - 1);
    b.m->smp_fire = hs;
    b.m->smp_t = uint32_t(s + 1);
    if (hs && frame[size_t(s + 1)]) want.push_back(uint32_t(s + 1));
    b.m->done = 0;
    if (word < 0 && b.m->pending && ((hs && frame[size_t(s + 2)]) || !tok)) {
      ASSERT_FALSE(want.empty()) << "clock " << c << ": a frame the rule does not pick";
      ASSERT_EQ(b.m->frame_t, want.front()) << "clock " << c;
      word = 0;
    }
    const bool reading = word >= 0 && word < 2 * kKs, releasing = word == 2 * kKs;
    if (reading) b.m->rd_addr = uint8_t(word);
    b.m->done = releasing;
    b.m->clk = 0;
    b.m->eval();
    if (tok) {
      EXPECT_TRUE(b.m->tok_ready) << "sample " << s << " token " << j;
    }
    b.tick();
    if (reading) {
      got.push_back(int32_t(b.m->rd_data));  // the word asked for one clock ago
      ++word;
    } else if (releasing) {
      const uint32_t f = want.front();
      for (int k = 0; k < kKs; ++k) {
        EXPECT_EQ(got[size_t(2 * k)], Bench::token(f, k, 0)) << "frame " << f << " k " << k;
        EXPECT_EQ(got[size_t(2 * k + 1)], Bench::token(f, k, 1)) << "frame " << f << " k " << k;
      }
      want.pop_front();
      got.clear();
      word = -1;
      ++frames;
    }
  }
  EXPECT_TRUE(want.empty());
  EXPECT_EQ(frames, 8);  // samples 31, 66, ..., 276
  EXPECT_EQ(b.m->overruns, 0);
}

}  // namespace
