// The bench that tests/rtl/dft_capture_test.cpp and sdft_front_test.cpp
// share: a Verilated sliding DFT (rtl/sdft_lanes.v) into rtl/frame_capture.v
// (tests/rtl/dft_capture_tb.v, sdft_front_tb.v), through the ports both
// benches have: the carriers' cfg_* stream, and the frame engine's side
// (pending, frame_t, rd_addr/rd_data, done). Each test drives its own
// sample stream (in_* or s_*) and checks its own pace.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hls/sdft_bank.h"

namespace dft_capture_bench {

template <class V>
struct Bench {
  std::unique_ptr<V> m = std::make_unique<V>();
  uint64_t cycle = 0;  // rising edges so far

  // One rising edge; inputs set before the call are sampled at it.
  void tick() {
    m->clk = 0;
    m->eval();
    m->clk = 1;
    m->eval();
    ++cycle;
  }
  // Three clocks of reset with the carriers' stream and the engine's side
  // idle (the caller's sample stream idle too).
  void reset() {
    m->rst = 1;
    m->cfg_valid = m->done = m->clear = 0;
    m->rd_addr = 0;
    for (int i = 0; i < 3; ++i) tick();
    m->rst = 0;
  }
  // Carriers 0..k-1 with random phase increments from `seed`, one cfg
  // handshake each, and the HLS kernel configured alike (nullptr if it
  // refuses them).
  template <class Bank>
  std::unique_ptr<Bank> configure(int k, uint64_t seed) {
    std::mt19937_64 rng(seed);
    typename Bank::Config cfg;
    cfg.carriers = k;
    for (int c = 0; c < k; ++c) {
      cfg.inc[c] = uint32_t(rng());
      m->cfg_valid = 1;
      m->cfg_k = uint8_t(c);
      m->cfg_inc = cfg.inc[c];
      m->cfg_last = c == k - 1;
      for (bool fire = false; !fire;) {
        m->clk = 0;
        m->eval();
        fire = m->cfg_ready;
        tick();
      }
    }
    m->cfg_valid = 0;
    auto bank = std::make_unique<Bank>();
    if (!bank->configure(cfg)) return nullptr;
    return bank;
  }
};

// The frame engine's side: reads each pending frame as soon as it is
// pending, word by word (rd_addr in one clock, rd_data after its edge), and
// releases it (done) in the clock after its 2 K words; each frame must be
// the next one expected, word for word.
struct FrameReader {
  struct Want {
    uint32_t t;
    std::vector<int32_t> words;
  };
  int k = 0;             // carriers: 2 K words a frame
  std::string context;   // put before the failure messages
  std::deque<Want> want;
  size_t wanted = 0, read = 0;
  int word = -1;         // the next word to read; -1: idle
  bool reading = false, releasing = false;
  std::vector<int32_t> got;

  // The frame of sample t: the kernel's tokens, re at 2 j, im at 2 j + 1.
  void expect(uint32_t t, const eskin::hls::SdftBankToken* toks) {
    Want w{t, {}};
    for (int j = 0; j < k; ++j) w.words.insert(w.words.end(), {toks[j].re, toks[j].im});
    want.push_back(std::move(w));
    ++wanted;
  }
  // In the clock's low half, before its eval: takes a frame just handed
  // over, and sets rd_addr and done.
  template <class V>
  ::testing::AssertionResult before_edge(V& m) {
    if (word < 0 && m.pending) {
      if (want.empty()) return ::testing::AssertionFailure() << context << "a frame the rule does not pick";
      if (m.frame_t != want.front().t)
        return ::testing::AssertionFailure() << context << "the pending frame's t: " << m.frame_t
                                             << ", expected " << want.front().t;
      word = 0;
    }
    reading = word >= 0 && word < 2 * k;
    releasing = word == 2 * k;
    if (reading) m.rd_addr = uint8_t(word);
    m.done = releasing;  // every word read: release the frame
    return ::testing::AssertionSuccess();
  }
  // After the clock's edge: the word asked for, or the released frame's
  // check.
  template <class V>
  void after_edge(const V& m) {
    if (reading) {
      got.push_back(int32_t(m.rd_data));
      ++word;
    } else if (releasing) {
      const Want& w = want.front();
      EXPECT_EQ(got, w.words) << context << "frame of sample " << w.t;
      ++read;
      want.pop_front();
      got.clear();
      word = -1;
    }
  }
};

}  // namespace dft_capture_bench
