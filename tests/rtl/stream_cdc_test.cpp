// rtl/stream_cdc.v: tokens cross from s_clk to m_clk in order, none lost or
// doubled, under random offers and random back-pressure, at clock ratios
// either way (the top's 40 MHz ADC into a 45 MHz core, its reverse, 12 to
// 50 MHz and back, and two equal clocks out of phase). Bounds, all from the
// module's header at SYNC = 2:
//  - the m side copies a token no sooner than SYNC whole m_clk periods
//    after the s side took it (the data register is then stable: only the
//    toggle went through the synchroniser);
//  - with m_ready high, m_valid shows a token within SYNC + 1 m_clk edges
//    of its take;
//  - with m_ready high, s_ready is back within SYNC + 1 m_clk edges plus
//    SYNC + 1 s_clk edges of a take (the rate the top's ADC relies on).
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <random>

#include "Vstream_cdc.h"
#include "two_clocks.h"

namespace {

constexpr int kSync = 2;

// s_clk = clock A, m_clk = clock B. p_offer / p_ready: percent chance that
// the source offers a token at an s_clk edge / that the sink is ready at an
// m_clk edge (100: always).
void run(double s_hz, double m_hz, int64_t phase_fs, int p_offer, int p_ready, int n_tokens,
         unsigned seed) {
  SCOPED_TRACE(testing::Message() << s_hz / 1e6 << " MHz -> " << m_hz / 1e6 << " MHz, offer "
                                  << p_offer << " %, ready " << p_ready << " %");
  Vstream_cdc m;
  TwoClocks clk(s_hz, m_hz, phase_fs);
  std::mt19937 rng(seed);
  std::deque<std::pair<uint16_t, int64_t>> in_flight;  // token, the time of its take
  uint16_t next = 0;
  int received = 0;
  bool offer = false, ready = false;
  int m_edges_since_take = -1;  // m_clk edges since the last take (-1: none yet)
  bool s_ready_due = false;      // s_ready not yet back since the last take
  int64_t in_flight_take_fs = 0;  // the last take
  bool prev_m_valid = false;
  m.s_clk = 0;
  m.m_clk = 0;
  m.s_rst = 1;
  m.m_rst = 1;
  m.s_valid = 0;
  m.m_ready = 0;
  m.eval();
  auto pulse = [&](const TwoClocks::Edge& e) {  // the rising edges at e, then both low
    m.s_clk = e.a;
    m.m_clk = e.b;
    m.eval();
    m.s_clk = 0;
    m.m_clk = 0;
    m.eval();
  };
  for (int i = 0; i < 8; ++i) pulse(clk.next());  // both resets overlap for a few edges of each
  m.s_rst = 0;
  m.m_rst = 0;
  while (received < n_tokens) {
    const auto e = clk.next();
    ASSERT_LT(e.t_fs, int64_t(1e15)) << "stalled: " << received << " tokens through";
    // Inputs for this edge (set after the previous edge, as registers would).
    if (e.a) {
      offer = int(rng() % 100) < p_offer && next < n_tokens;
      m.s_valid = offer;
      m.s_data = next;
    }
    if (e.b) {
      ready = int(rng() % 100) < p_ready;
      m.m_ready = ready;
    }
    m.eval();
    // What the edge samples.
    const bool took = e.a && offer && m.s_ready;
    const bool gave = e.b && m.m_valid && ready;
    if (gave) {
      ASSERT_FALSE(in_flight.empty()) << "a token nobody sent: " << m.m_data;
      ASSERT_EQ(m.m_data, in_flight.front().first) << "out of order or lost";
      in_flight.pop_front();
      ++received;
    }
    pulse(e);
    if (e.b && m_edges_since_take >= 0) ++m_edges_since_take;
    if (took) {
      in_flight.push_back({next, e.t_fs});
      ++next;
      m_edges_since_take = 0;
      s_ready_due = true;
      in_flight_take_fs = e.t_fs;
    }
    // A copy into m_data: m_valid rises, or a new token replaces one taken.
    const bool copied = m.m_valid && (!prev_m_valid || gave) && e.b;
    if (copied) {
      // The token now shown is the oldest not yet given.
      ASSERT_FALSE(in_flight.empty());
      const auto& [tok, t_take] = in_flight.front();
      ASSERT_EQ(m.m_data, tok);
      EXPECT_GE(e.t_fs - t_take, kSync * clk.period_b)
          << "token " << tok << " copied before its data register was stable";
      if (p_ready == 100 && tok == next - 1) {
        EXPECT_LE(m_edges_since_take, kSync + 1) << "token " << tok << " late to m_valid";
      }
    }
    if (p_ready == 100 && s_ready_due && m.s_ready) {
      EXPECT_LE(e.t_fs - in_flight_take_fs, (kSync + 1) * (clk.period_a + clk.period_b))
          << "s_ready late after token " << next - 1;
      s_ready_due = false;
    }
    prev_m_valid = m.m_valid;
  }
  EXPECT_EQ(next, n_tokens);
  EXPECT_TRUE(in_flight.empty());
}

struct Ratio {
  double s_hz, m_hz;
  int64_t phase_fs;
};
constexpr Ratio kRatios[] = {
    {40e6, 45e6, 3'000'000}, {45e6, 40e6, 0}, {12e6, 50e6, 7'000'000},
    {50e6, 12e6, 1'000'000}, {40e6, 40e6, 12'500'000},  // equal clocks, half a period apart
};

TEST(StreamCdc, EveryTokenCrossesInOrderUnderBackPressure) {
  unsigned seed = 1;
  for (const auto& r : kRatios)
    for (int p_ready : {100, 60, 15}) run(r.s_hz, r.m_hz, r.phase_fs, 70, p_ready, 3000, seed++);
}

TEST(StreamCdc, BackToBackOffersMeetTheLatencyBounds) {
  unsigned seed = 100;
  for (const auto& r : kRatios) run(r.s_hz, r.m_hz, r.phase_fs, 100, 100, 3000, seed++);
}

}  // namespace
