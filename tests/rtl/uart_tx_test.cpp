// rtl/uart_tx.v: exact 8N1 waveform, cycle by cycle.
//
// Bound: exact. For a byte b accepted at handshake edge h, the line must be
// 0 (start) in the CPB cycles after h, then bit i of b (LSB first) in the
// i-th following CPB-cycle slot, then 1 (stop) for CPB cycles; CPB =
// round(CLK_HZ / BAUD) (4 for 12 MHz / 3 Mbaud, 417 for 48 MHz / 115200),
// computed here from the clock and baud, not read from the RTL. With a
// source that always has data, handshakes are exactly 10 * CPB cycles apart
// (no idle bit between bytes); with random gaps the line idles high.
// The cycle level's C++ model (sim/cycle/uart_tx.h) gives the same tx and
// s_ready as the RTL at every clock, at both rates (bound: exact).
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "Vuart_tx.h"
#include "Vuart_tx_slow.h"
#include "sim/cycle/uart_tx.h"

namespace {

struct Sent { uint64_t edge; uint8_t byte; };

template <class M>
void run(int cpb, int nbytes, double p_offer, uint64_t seed) {
  auto m = std::make_unique<M>();
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution offer(p_offer);
  m->clk = 0; m->rst = 1; m->s_valid = 0; m->s_data = 0;
  for (int i = 0; i < 3; ++i) { m->clk = 1; m->eval(); m->clk = 0; m->eval(); }
  m->rst = 0; m->eval();
  std::vector<Sent> sent;
  std::vector<uint8_t> line;  // tx after each edge
  uint64_t edge = 0;
  int remaining = nbytes;
  bool valid = false;
  uint8_t data = 0;
  while (remaining > 0 || edge < (sent.empty() ? 0 : sent.back().edge + 12 * uint64_t(cpb))) {
    if (!valid && remaining > 0 && offer(rng)) { valid = true; data = uint8_t(rng()); }
    m->s_valid = valid; m->s_data = data;
    m->eval();
    const bool hs = valid && m->s_ready;
    m->clk = 1; m->eval();
    ++edge;
    line.push_back(m->tx);
    m->clk = 0; m->eval();
    if (hs) { sent.push_back({edge, data}); valid = false; --remaining; }
  }
  ASSERT_EQ(int(sent.size()), nbytes);
  // Expected waveform: idle 1, each frame starting the cycle after its edge.
  std::vector<uint8_t> want(line.size(), 1);
  for (const Sent& s : sent) {
    for (int slot = 0; slot < 10; ++slot) {
      const int level = slot == 0 ? 0 : slot == 9 ? 1 : (s.byte >> (slot - 1)) & 1;
      for (int c = 0; c < cpb; ++c) {
        const uint64_t idx = s.edge - 1 + uint64_t(slot) * cpb + c;  // line[j]: after edge j+1
        if (idx < want.size()) want[idx] = uint8_t(level);
      }
    }
  }
  for (size_t i = 0; i < line.size(); ++i) ASSERT_EQ(line[i], want[i]) << "cycle " << i;
  for (size_t i = 1; i < sent.size(); ++i) ASSERT_GE(sent[i].edge - sent[i - 1].edge, 10u * cpb);
  if (p_offer >= 1.0) {
    for (size_t i = 1; i < sent.size(); ++i) ASSERT_EQ(sent[i].edge - sent[i - 1].edge, 10u * cpb);
  }
}

template <class M>
void same_as_model(uint64_t clk_hz, uint64_t baud, int nbytes, double p_offer, uint64_t seed) {
  auto m = std::make_unique<M>();
  eskin::cycle::UartTx model(clk_hz, baud);
  model.reset();
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution offer(p_offer);
  m->clk = 0; m->rst = 1; m->s_valid = 0; m->s_data = 0;
  for (int i = 0; i < 3; ++i) { m->clk = 1; m->eval(); m->clk = 0; m->eval(); }
  m->rst = 0; m->eval();
  bool valid = false;
  uint8_t data = 0;
  int taken = 0;
  for (uint64_t cyc = 0; taken < nbytes || cyc % (20 * model.clocks_per_bit()) != 0; ++cyc) {
    if (!valid && taken < nbytes && offer(rng)) { valid = true; data = uint8_t(rng()); }
    m->s_valid = valid; m->s_data = data;
    m->eval();
    ASSERT_EQ(bool(m->s_ready), model.s_ready()) << "cycle " << cyc;
    ASSERT_EQ(bool(m->tx), model.tx()) << "cycle " << cyc;
    const bool hs = valid && model.s_ready();
    model.clock(valid, data);
    m->clk = 1; m->eval(); m->clk = 0; m->eval();
    if (hs) { valid = false; ++taken; }
  }
}

}  // namespace

TEST(UartTx, CycleModelEqualsTheRtlEveryClock) {
  same_as_model<Vuart_tx>(12000000, 3000000, 400, 1.0, 5);
  same_as_model<Vuart_tx>(12000000, 3000000, 400, 0.05, 6);
  same_as_model<Vuart_tx_slow>(48000000, 115200, 30, 0.01, 7);
}

TEST(UartTx, BackToBackAt3Mbaud) { run<Vuart_tx>(12000000 / 3000000, 300, 1.0, 1); }
TEST(UartTx, RandomGapsAt3Mbaud) { run<Vuart_tx>(4, 300, 0.05, 2); }
TEST(UartTx, BackToBackAt115200From48MHz) {
  const int cpb = int((48000000 + 115200 / 2) / 115200);
  ASSERT_EQ(cpb, 417);
  run<Vuart_tx_slow>(cpb, 20, 1.0, 3);
}
TEST(UartTx, RandomGapsAt115200From48MHz) { run<Vuart_tx_slow>(417, 20, 0.002, 4); }
