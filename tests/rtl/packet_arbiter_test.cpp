// rtl/packet_arbiter.v (NS = 3), which lets two tops share one link_framer
// (rtl/mixed_top.v): three sources offer packets (type, t, len, payload) of
// random lengths, pausing at random inside them, into a sink that stalls at
// random. Checked:
//   - the output, cut into packets by their len fields, is exactly each
//     source's packets, whole and in order (a packet split by another's
//     bytes would not parse back into the sources' packets);
//   - data are stable while the sink stalls;
//   - fairness: from the clock a source offers a packet, at most NS - 1 = 2
//     packets of other sources start before it (round robin);
//   - with every source always ready and the sink never stalling, a packet
//     of L bytes takes exactly L + 1 clocks (one clock to grant).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "Vpacket_arbiter.h"
#include "clocked_dut.h"

namespace {

constexpr int kNs = 3;
using Bytes = std::vector<uint8_t>;

// A packet of source s: type 0x40 + s, t = its index, len bytes of payload.
Bytes make_packet(int s, uint32_t idx, size_t len, std::mt19937& rng) {
  Bytes p{uint8_t(0x40 + s), uint8_t(idx), uint8_t(idx >> 8), uint8_t(idx >> 16),
          uint8_t(idx >> 24), uint8_t(len), uint8_t(len >> 8)};
  for (size_t i = 0; i < len; ++i) p.push_back(uint8_t(rng()));
  return p;
}

struct Bench : ClockedDut<Vpacket_arbiter> {
  Bench() {
    m.s_valid = 0;
    m.m_ready = 0;
    m.rst = 1;
    tick();
    tick();
    m.rst = 0;
  }
};

struct Source {
  std::deque<Bytes> todo;  // packets still to send (front: being sent)
  size_t pos = 0;          // next byte of todo.front()
  bool offering = false;   // s_valid high (kept until taken)
  uint64_t offered_at_start = 0;  // packets started on the output when this one was first offered
};

TEST(PacketArbiter, WholePacketsInOrderFairUnderRandomStalls) {
  Bench b;
  std::mt19937 rng(11);
  std::array<Source, kNs> src;
  std::array<std::deque<Bytes>, kNs> expect;
  for (int s = 0; s < kNs; ++s)
    for (uint32_t i = 0; i < 120; ++i) {
      const size_t len = (rng() % 5 == 0) ? 0 : rng() % 60;  // empty packets too
      src[size_t(s)].todo.push_back(make_packet(s, i, len, rng));
      expect[size_t(s)].push_back(src[size_t(s)].todo.back());
    }
  Bytes out;            // the output packet being collected
  uint64_t started = 0; // output packets whose first byte has passed
  size_t done = 0;
  int worst_wait = 0;
  bool stalled = false;
  uint8_t held = 0;
  for (int cycle = 0; cycle < 400000 && done < size_t(kNs) * 120; ++cycle) {
    uint32_t valid = 0, data = 0;
    for (int s = 0; s < kNs; ++s) {
      Source& so = src[size_t(s)];
      if (!so.offering && !so.todo.empty() && rng() % 100 < 40) {
        so.offering = true;
        if (so.pos == 0) so.offered_at_start = started;
      }
      if (so.offering) {
        valid |= 1u << s;
        data |= uint32_t(so.todo.front()[so.pos]) << (8 * s);
      }
    }
    b.m.s_valid = valid;
    b.m.s_data = data;
    b.m.m_ready = rng() % 100 < 60;
    b.m.eval();
    if (stalled) {
      ASSERT_TRUE(b.m.m_valid) << "cycle " << cycle;
      ASSERT_EQ(b.m.m_data, held) << "data changed while stalled, cycle " << cycle;
    }
    const bool fire = b.m.m_valid && b.m.m_ready;
    stalled = b.m.m_valid && !b.m.m_ready;
    held = b.m.m_data;
    int taken = -1;
    for (int s = 0; s < kNs; ++s)
      if ((b.m.s_ready >> s) & 1) {
        ASSERT_EQ(taken, -1) << "two sources ready at once";
        taken = s;
      }
    ASSERT_EQ(fire, taken >= 0 && ((valid >> taken) & 1)) << "cycle " << cycle;
    if (fire) {
      Source& so = src[size_t(taken)];
      ASSERT_EQ(b.m.m_data, so.todo.front()[so.pos]);
      if (so.pos == 0) {
        worst_wait = std::max(worst_wait, int(started - so.offered_at_start));
        ++started;
      }
      out.push_back(b.m.m_data);
      so.offering = false;
      if (++so.pos == so.todo.front().size()) {
        so.todo.pop_front();
        so.pos = 0;
      }
      if (out.size() >= 7 && out.size() == 7u + (out[5] | (out[6] << 8))) {
        const int s = out[0] - 0x40;
        ASSERT_TRUE(s >= 0 && s < kNs) << "packet type " << int(out[0]);
        ASSERT_FALSE(expect[size_t(s)].empty());
        ASSERT_EQ(out, expect[size_t(s)].front()) << "packet " << done << " of source " << s;
        expect[size_t(s)].pop_front();
        out.clear();
        ++done;
      }
    }
    b.tick();
  }
  EXPECT_EQ(done, size_t(kNs) * 120);
  EXPECT_TRUE(out.empty());
  EXPECT_LE(worst_wait, kNs - 1) << "a source waited for more than NS - 1 other packets";
  EXPECT_EQ(worst_wait, kNs - 1) << "the random run never made a source wait a full round";
}

TEST(PacketArbiter, FullRateIsOneGrantClockPerPacket) {
  Bench b;
  std::mt19937 rng(5);
  std::array<std::deque<Bytes>, kNs> todo;
  std::array<size_t, kNs> pos{};
  uint64_t want_cycles = 0;
  for (int s = 0; s < kNs; ++s)
    for (uint32_t i = 0; i < 30; ++i) {
      todo[size_t(s)].push_back(make_packet(s, i, rng() % 40, rng));
      want_cycles += todo[size_t(s)].back().size() + 1;  // L bytes + the grant clock
    }
  b.m.m_ready = 1;
  uint64_t cycles = 0;
  std::vector<int> order;  // source of each packet, in output order
  for (;;) {
    uint32_t valid = 0, data = 0;
    for (int s = 0; s < kNs; ++s)
      if (!todo[size_t(s)].empty()) {
        valid |= 1u << s;
        data |= uint32_t(todo[size_t(s)].front()[pos[size_t(s)]]) << (8 * s);
      }
    if (!valid) break;
    b.m.s_valid = valid;
    b.m.s_data = data;
    b.m.eval();
    for (int s = 0; s < kNs; ++s)
      if ((b.m.s_ready >> s) & 1 && (valid >> s) & 1) {
        if (pos[size_t(s)] == 0) order.push_back(s);
        if (++pos[size_t(s)] == todo[size_t(s)].front().size()) {
          todo[size_t(s)].pop_front();
          pos[size_t(s)] = 0;
        }
      }
    b.tick();
    ++cycles;
    ASSERT_LT(cycles, 100000u);
  }
  EXPECT_EQ(cycles, want_cycles);
  // All three always waiting: strict rotation 0, 1, 2, 0, ... (reset grant
  // is source 0, so the first pick after it is source 1).
  for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], int((i + 1) % kNs)) << "packet " << i;
}

}  // namespace
