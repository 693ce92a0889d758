// rtl/uart_rx.v driven by an independent bit-level 8N1 generator.
//
// Bounds and why:
//  * Exact baud: every byte arrives intact, and m_valid rises exactly
//    2 + CPB/2 + 9*CPB edges after the first edge that sees the start bit
//    (2 synchroniser flops, half a bit to the start-bit middle, 9 bit
//    periods to the stop-bit middle), CPB = round(CLK_HZ/BAUD).
//  * Baud error: the last sample (stop bit) sits at 9*CPB + CPB/2 + [0,1)
//    cycles after the true start edge and must fall inside the stop bit
//    [9 Tb, 10 Tb), Tb = CPB (1 + e). For CPB = 4 that holds for |e| <= 2%
//    (sample 38..39 in [35.28, 39.2) .. [36.72, 40.8)); for CPB = 417 for
//    |e| <= 4% ([3602.9, 4003.2) .. [3903.1, 4336.8) around 3961..3962).
//  * Stop bit 0 -> frame_err pulse, byte dropped, next byte fine.
//  * A low glitch shorter than CPB/2 is not a start bit.
//  * Consumer stalled over two bytes: the first is held, the second dropped
//    with an overrun pulse.
//  * The cycle level's C++ model (sim/cycle/uart_rx.h) gives the same
//    m_valid, m_data, frame_err and overrun as the RTL at every clock, on a
//    line of random frames, gaps, glitches and spoiled stop bits with a
//    random consumer, at both rates (bound: exact).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "Vuart_rx.h"
#include "Vuart_rx_slow.h"
#include "sim/cycle/uart_rx.h"

namespace {

template <class M>
struct Rx {
  std::unique_ptr<M> m = std::make_unique<M>();
  uint64_t edge = 0;
  std::vector<uint8_t> got;
  std::vector<uint64_t> valid_edge;  // edge after which each byte became valid
  int frame_errs = 0, overruns = 0;
  bool ready = true;

  Rx() {
    m->clk = 0; m->rst = 1; m->rx = 1; m->m_ready = 1;
    for (int i = 0; i < 3; ++i) step(1);
    m->rst = 0;
    got.clear(); valid_edge.clear();
  }
  void step(int level) {
    m->rx = uint8_t(level);
    m->m_ready = ready;
    m->eval();
    const bool take = m->m_valid && ready;
    if (take) got.push_back(m->m_data);
    m->clk = 1; m->eval(); ++edge;
    m->clk = 0; m->eval();
    if (m->m_valid && !take && (valid_edge.size() < got.size() + 1)) valid_edge.push_back(edge);
    if (m->frame_err) ++frame_errs;
    if (m->overrun) ++overruns;
  }
  // Sends one 8N1 frame with bit period tb cycles (fractional: the line
  // changes at the first edge at or after each ideal bit boundary).
  void send(uint8_t b, double tb, int stop = 1, double idle_bits = 0) {
    const uint64_t t0 = edge;
    for (int slot = 0; slot < 10; ++slot) {
      const int level = slot == 0 ? 0 : slot == 9 ? stop : (b >> (slot - 1)) & 1;
      while (double(edge - t0) < std::ceil((slot + 1) * tb)) step(level);
    }
    while (double(edge - t0) < std::ceil((10 + idle_bits) * tb)) step(1);
  }
  void idle(int n) { for (int i = 0; i < n; ++i) step(1); }
};

template <class M>
void random_bytes(int cpb, double err, int n, uint64_t seed) {
  Rx<M> rx;
  std::mt19937_64 rng(seed);
  std::vector<uint8_t> sent;
  for (int i = 0; i < n; ++i) {
    const uint8_t b = uint8_t(rng());
    sent.push_back(b);
    rx.send(b, cpb * (1.0 + err), 1, (i % 4 == 0) ? 1.7 : 0.0);
  }
  rx.idle(2 * cpb);
  EXPECT_EQ(rx.got, sent) << "err " << err;
  EXPECT_EQ(rx.frame_errs, 0);
}

// The line for same_as_model: random frames back to back or after gaps,
// some with a spoiled stop bit, and low glitches shorter than a bit.
std::vector<uint8_t> random_line(int cpb, int frames, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<uint8_t> line(size_t(3 * cpb), 1);
  for (int f = 0; f < frames; ++f) {
    const int kind = int(rng() % 10);
    if (kind == 0) {  // a glitch: low for 1 .. cpb - 1 clocks
      line.insert(line.end(), size_t(1 + rng() % uint64_t(cpb - 1)), 0);
      line.insert(line.end(), size_t(cpb), 1);
      continue;
    }
    const uint8_t b = uint8_t(rng());
    for (int slot = 0; slot < 10; ++slot) {
      const int level = slot == 0 ? 0 : slot == 9 ? (kind == 1 ? 0 : 1) : (b >> (slot - 1)) & 1;
      line.insert(line.end(), size_t(cpb), uint8_t(level));
    }
    if (kind == 1) line.insert(line.end(), size_t(cpb), 1);  // the line returns high
    if (kind == 2) line.insert(line.end(), size_t(rng() % uint64_t(4 * cpb)), 1);
  }
  line.insert(line.end(), size_t(12 * cpb), 1);
  return line;
}

template <class M>
void same_as_model(uint64_t clk_hz, uint64_t baud, int frames, double p_ready, bool overruns_expected,
                   uint64_t seed) {
  auto m = std::make_unique<M>();
  eskin::cycle::UartRx model(clk_hz, baud);
  model.reset();
  const int cpb = int((clk_hz + baud / 2) / baud);
  const auto line = random_line(cpb, frames, seed);
  std::mt19937_64 rng(seed + 1);
  std::bernoulli_distribution ready(p_ready);
  m->clk = 0; m->rst = 1; m->rx = 1; m->m_ready = 1;
  for (int i = 0; i < 3; ++i) { m->clk = 1; m->eval(); m->clk = 0; m->eval(); }
  m->rst = 0;
  int bytes = 0, errors = 0, overruns = 0;
  for (size_t c = 0; c < line.size(); ++c) {
    const bool rdy = ready(rng);
    m->rx = line[c];
    m->m_ready = rdy;
    m->eval();
    ASSERT_EQ(bool(m->m_valid), model.m_valid()) << "clock " << c;
    ASSERT_EQ(m->m_data, model.m_data()) << "clock " << c;
    ASSERT_EQ(bool(m->frame_err), model.frame_err()) << "clock " << c;
    ASSERT_EQ(bool(m->overrun), model.overrun()) << "clock " << c;
    bytes += model.m_valid() && rdy;
    errors += model.frame_err();
    overruns += model.overrun();
    model.clock(line[c] != 0, rdy);
    m->clk = 1; m->eval(); m->clk = 0; m->eval();
  }
  // The line exercised every path (an overrun needs a consumer slower than
  // the line).
  EXPECT_GT(bytes, frames / 4);
  EXPECT_GT(errors, 0);
  EXPECT_EQ(overruns > 0, overruns_expected);
}

}  // namespace

TEST(UartRx, CycleModelEqualsTheRtlEveryClock) {
  same_as_model<Vuart_rx>(12000000, 3000000, 600, 1.0, false, 21);
  same_as_model<Vuart_rx>(12000000, 3000000, 600, 0.01, true, 22);
  same_as_model<Vuart_rx_slow>(48000000, 115200, 60, 0.3, false, 23);
}

TEST(UartRx, ExactLatencyAt3Mbaud) {
  const int cpb = 12000000 / 3000000;
  Rx<Vuart_rx> rx;
  rx.idle(5);
  const uint64_t first_low = rx.edge + 1;  // the next step drives rx low
  rx.send(0xA5, cpb);
  rx.idle(cpb);
  ASSERT_EQ(rx.got, std::vector<uint8_t>{0xA5});
  ASSERT_EQ(rx.valid_edge.size(), 1u);
  EXPECT_EQ(rx.valid_edge[0] - first_low, uint64_t(2 + cpb / 2 + 9 * cpb));
}

TEST(UartRx, ExactLatencyAt115200From48MHz) {
  const int cpb = (48000000 + 57600) / 115200;
  Rx<Vuart_rx_slow> rx;
  rx.idle(5);
  const uint64_t first_low = rx.edge + 1;
  rx.send(0x3C, cpb);
  rx.idle(cpb);
  ASSERT_EQ(rx.got, std::vector<uint8_t>{0x3C});
  EXPECT_EQ(rx.valid_edge.at(0) - first_low, uint64_t(2 + cpb / 2 + 9 * cpb));
}

TEST(UartRx, RandomBytesWithBaudError3Mbaud) {
  for (double e : {0.0, -0.02, 0.02}) random_bytes<Vuart_rx>(4, e, 400, 11);
}

TEST(UartRx, RandomBytesWithBaudError115200) {
  for (double e : {0.0, -0.04, 0.04}) random_bytes<Vuart_rx_slow>(417, e, 30, 12);
}

TEST(UartRx, FramingErrorDropsByteAndRecovers) {
  Rx<Vuart_rx> rx;
  rx.send(0x11, 4);
  rx.send(0x22, 4, /*stop=*/0);
  rx.idle(8);
  rx.send(0x33, 4);
  rx.idle(8);
  EXPECT_EQ(rx.got, (std::vector<uint8_t>{0x11, 0x33}));
  EXPECT_EQ(rx.frame_errs, 1);
}

TEST(UartRx, ShortGlitchIsIgnored) {
  Rx<Vuart_rx_slow> rx;
  rx.idle(10);
  for (int i = 0; i < 417 / 2 - 3; ++i) rx.step(0);  // shorter than half a bit
  rx.idle(2000);
  rx.send(0x5A, 417);
  rx.idle(417);
  EXPECT_EQ(rx.got, std::vector<uint8_t>{0x5A});
  EXPECT_EQ(rx.frame_errs, 0);
}

TEST(UartRx, OverrunWhenConsumerStalls) {
  Rx<Vuart_rx> rx;
  rx.ready = false;
  rx.send(0x01, 4);
  rx.send(0x02, 4);
  rx.idle(4);
  EXPECT_EQ(rx.overruns, 1);
  rx.ready = true;
  rx.idle(2);
  rx.send(0x03, 4);
  rx.idle(8);
  EXPECT_EQ(rx.got, (std::vector<uint8_t>{0x01, 0x03}));
}
