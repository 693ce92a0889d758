// rtl/spike_encoder.v against hls/spike_encoder.h (SpikeEncoder, its
// close_packet the SPIKES packet hls/dtmf_chain.h sends), byte for byte, at
// MAX 256 (Vspike_encoder, the default skins' window) and MAX 4096
// (Vspike_encoder_4096, a 64x64 skin's layer of events; spike_encoder_test.cmake).
//
// Bound: exact. The block only stores and moves bytes (and one 16-bit
// subtraction, the kernel's), so its bytes must be the kernel's packets'
// FIFO bytes in order and spikes_dropped the kernel's dropped(). Checked:
//   - random windows of 1..3 frames (t random, so dt wraps mod 2^16), each
//     frame's layer-0 spikes then layer-1 spikes, windows over MAX (the
//     rest counted), closes with no event (no packet), frames sent while a
//     window is open (no reopening), under random in_valid and out_ready
//     (seeded); out_data holds while the output stalls;
//   - the drop count past 65535 events over MAX in one window: it saturates
//     there, as the kernel's (the STATUS field is u16);
//   - the room rule at the byte, into a FIFO nobody reads;
//   - timing with every stream ready: a command a clock; the packet's first
//     byte taken 3 edges after the close's handshake, one byte a clock to
//     its last; the next command 1 edge after the last byte.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "Vspike_encoder.h"
#include "Vspike_encoder_4096.h"
#include "clocked_dut.h"
#include "hls/spike_encoder.h"

namespace {

namespace hls = eskin::hls;
using Bytes = std::vector<uint8_t>;

enum Op : uint8_t { kFrame = 0, kSpike = 1, kClose = 2 };
struct Cmd {
  Op op = kFrame;
  uint32_t t = 0;
  uint8_t layer = 0;
  uint16_t neuron = 0;
};

template <class V, int MAX>
struct Bench : ClockedDut<V> {
  static constexpr int kMax = MAX;
  using ClockedDut<V>::m;
  using ClockedDut<V>::cycle;
  using ClockedDut<V>::tick;

  struct Packet {
    uint8_t type = 0;
    uint32_t t = 0;
    uint16_t len = 0;
    uint8_t payload[MAX * hls::kSpikeEventBytes] = {};
  };

  std::unique_ptr<hls::SpikeEncoder<MAX>> enc = std::make_unique<hls::SpikeEncoder<MAX>>();
  std::unique_ptr<Packet> pkt = std::make_unique<Packet>();
  std::mt19937 rng;
  double p_in = 1.0, p_out = 1.0;
  int fifo_depth = 0;  // > 0: out_free from a FIFO of this size that nobody reads
  std::vector<Cmd> cmds;
  std::vector<Bytes> expect;  // the kernel's packets, FIFO bytes
  std::vector<size_t> close_cmd;  // per expected packet: its close's command index

  Bytes out;
  std::vector<uint64_t> out_edge, cmd_edge;
  int drops = 0;
  size_t fifo_used = 0;
  bool overflow = false;

  explicit Bench(uint32_t seed) : rng(seed) {
    m.out_free = 0xFFFF;
    this->reset();
  }

  void add(const Cmd& c) {
    cmds.push_back(c);
    if (c.op == kFrame) enc->frame(c.t);
    if (c.op == kSpike) enc->spike(c.layer, c.neuron);
    if (c.op == kClose && enc->close_packet(*pkt)) {
      const Packet& p = *pkt;
      Bytes b{p.type,        uint8_t(p.t),       uint8_t(p.t >> 8), uint8_t(p.t >> 16),
              uint8_t(p.t >> 24), uint8_t(p.len), uint8_t(p.len >> 8)};
      b.insert(b.end(), p.payload, p.payload + p.len);
      expect.push_back(b);
      close_cmd.push_back(cmds.size() - 1);
    }
  }

  // A window of `frames` frames with up to `per_layer` spikes a layer each.
  void window(int frames, int per_layer) {
    for (int f = 0; f < frames; ++f) {
      add({kFrame, uint32_t(rng()), 0, 0});
      for (uint8_t layer = 0; layer < 2; ++layer) {
        const int n = int(rng() % uint32_t(per_layer + 1));
        uint16_t neuron = uint16_t(rng() % 16);
        for (int k = 0; k < n; ++k, neuron = uint16_t(neuron + 1 + rng() % 9))
          add({kSpike, 0, layer, neuron});
      }
    }
    add({kClose, 0, 0, 0});
  }

  bool coin(double p) { return p >= 1.0 || std::uniform_real_distribution<double>(0, 1)(rng) < p; }

  void run() {
    size_t next = 0;
    bool held = false;
    uint8_t held_data = 0;
    size_t want = 0;
    for (const auto& e : expect) want += e.size();
    const uint64_t deadline = cycle + 50 * (cmds.size() + want) + 1000;
    while (cycle < deadline && !(next == cmds.size() && m.in_ready && !m.out_valid)) {
      m.in_valid = next < cmds.size() && coin(p_in);
      if (m.in_valid) {
        m.in_op = cmds[next].op;
        m.in_t = cmds[next].t;
        m.in_layer = cmds[next].layer;
        m.in_neuron = cmds[next].neuron;
      }
      if (fifo_depth > 0) {
        m.out_free = uint16_t(fifo_depth - int(fifo_used));
        m.out_ready = 1;
      } else {
        m.out_ready = coin(p_out);
      }
      m.eval();
      if (held) {
        EXPECT_TRUE(m.out_valid) << "byte withdrawn while stalled";
        EXPECT_EQ(m.out_data, held_data) << "out_data changed while stalled, byte " << out.size();
      }
      const bool take = m.in_valid && m.in_ready;
      const bool out_take = m.out_valid && m.out_ready;
      if (out_take) {
        out.push_back(m.out_data);
        out_edge.push_back(cycle + 1);
        if (fifo_depth > 0) {
          if (fifo_used == size_t(fifo_depth)) overflow = true;
          else ++fifo_used;
        }
      }
      held = m.out_valid && !m.out_ready;
      held_data = m.out_data;
      tick();
      if (m.dropped) ++drops;
      if (take) cmd_edge.push_back(cycle), ++next;
    }
    ASSERT_LT(cycle, deadline) << "the block did not finish";
  }

  void check_exact() {
    Bytes want;
    for (const auto& e : expect) want.insert(want.end(), e.begin(), e.end());
    ASSERT_EQ(out.size(), want.size());
    for (size_t i = 0; i < want.size(); ++i) ASSERT_EQ(out[i], want[i]) << "byte " << i;
    EXPECT_EQ(m.spikes_dropped, enc->dropped());
    EXPECT_EQ(drops, 0);
  }
};

using B256 = Bench<Vspike_encoder, 256>;
using B4096 = Bench<Vspike_encoder_4096, 4096>;

template <class B>
void random_windows(uint32_t seed, int windows, int per_layer, double p_in, double p_out) {
  auto b = std::make_unique<B>(seed);
  b->p_in = p_in;
  b->p_out = p_out;
  for (int w = 0; w < windows; ++w) {
    if (w % 7 == 3) b->add({kClose, 0, 0, 0});  // a close with nothing open: no packet
    b->window(1 + int(b->rng() % 3), w % 5 == 4 ? 0 : per_layer);
  }
  b->run();
  b->check_exact();
  EXPECT_GT(b->enc->dropped(), 0u) << "no window over MAX: the drop rule untested";
  EXPECT_GT(b->expect.size(), size_t(windows) / 2);
}

TEST(SpikeEncoder, Max256ByteExactUnderRandomValidAndBackPressure) {
  random_windows<B256>(1, 60, 70, 0.6, 0.5);
  random_windows<B256>(2, 60, 70, 0.95, 0.2);
  random_windows<B256>(3, 60, 70, 0.2, 0.95);
}

TEST(SpikeEncoder, Max4096ByteExactUnderRandomValidAndBackPressure) {
  random_windows<B4096>(4, 6, 1000, 0.6, 0.5);
}

// 256 + 65540 events in one window: the kernel's count stops at 65535 and
// so must the block's (a 32-bit counter that kept going reads 65540).
TEST(SpikeEncoder, Max256DropCountSaturatesAt65535) {
  auto b = std::make_unique<B256>(11);
  b->add({kFrame, 1000, 0, 0});
  for (int k = 0; k < 256 + 65540; ++k) b->add({kSpike, 0, uint8_t(k & 1), uint16_t(k % 9)});
  b->add({kClose, 0, 0, 0});
  ASSERT_EQ(b->enc->dropped(), 65535u);
  b->run();
  b->check_exact();
}

// `clear` (the top's CLEAR_COUNTERS) zeroes the count, and wins over a
// drop in its own clock: after 65540 drops (saturated at 65535) a clear
// gives 0; then a window of 256 + 3 events counts 3 again, the last of
// them taken in the clear's clock, which leaves 2.
TEST(SpikeEncoder, ClearZeroesTheDropCount) {
  auto b = std::make_unique<B256>(12);
  b->add({kFrame, 1000, 0, 0});
  for (int k = 0; k < 256 + 65540; ++k) b->add({kSpike, 0, uint8_t(k & 1), uint16_t(k % 9)});
  b->add({kClose, 0, 0, 0});
  b->run();
  b->check_exact();
  ASSERT_EQ(b->m.spikes_dropped, 65535u);
  b->m.clear = 1;
  b->tick();
  b->m.clear = 0;
  EXPECT_EQ(b->m.spikes_dropped, 0u);
  // A new window past MAX, its third drop in a clear's clock.
  auto op = [&](uint8_t o, uint32_t t, uint16_t n) {
    b->m.in_valid = 1;
    b->m.in_op = o;
    b->m.in_t = t;
    b->m.in_layer = 0;
    b->m.in_neuron = n;
    for (int i = 0; i < 1000 && !b->m.in_ready; ++i) b->tick();
    ASSERT_TRUE(b->m.in_ready);
  };
  op(kFrame, 2000, 0);
  b->tick();
  for (int k = 0; k < 256 + 3; ++k) {
    op(kSpike, 0, uint16_t(k % 9));
    if (k == 256 + 2) b->m.clear = 1;
    b->tick();
    b->m.clear = 0;
  }
  b->m.in_valid = 0;
  b->tick();
  EXPECT_EQ(b->m.spikes_dropped, 0u) << "the clear's clock drops nothing into the count";
  op(kSpike, 0, 1);
  b->tick();
  b->m.in_valid = 0;
  b->tick();
  EXPECT_EQ(b->m.spikes_dropped, 1u);
}

TEST(SpikeEncoder, Max256RoomRuleAtTheByte) {
  for (int extra : {0, -1}) {
    auto b = std::make_unique<B256>(5);
    b->add({kFrame, 1000, 0, 0});
    for (uint16_t k = 0; k < 3; ++k) b->add({kSpike, 0, uint8_t(k & 1), k});
    b->add({kClose, 0, 0, 0});
    const int need = 7 + 15;
    b->fifo_depth = need + extra;
    b->run();
    EXPECT_FALSE(b->overflow);
    if (extra == 0) {
      EXPECT_EQ(b->out, b->expect.at(0));
      EXPECT_EQ(b->drops, 0);
    } else {
      EXPECT_TRUE(b->out.empty());
      EXPECT_EQ(b->drops, 1);
    }
  }
}

TEST(SpikeEncoder, Max256ExactTimingOneByteAClock) {
  auto b = std::make_unique<B256>(6);
  for (int w = 0; w < 20; ++w) b->window(1 + w % 3, 40);
  b->run();
  b->check_exact();
  ASSERT_EQ(b->cmd_edge.size(), b->cmds.size());
  std::vector<bool> after_packet(b->cmds.size() + 1, false);
  size_t byte = 0;
  for (size_t p = 0; p < b->expect.size(); ++p) {
    const size_t c = b->close_cmd[p];
    const uint64_t first = b->out_edge[byte];
    EXPECT_EQ(first, b->cmd_edge[c] + 3) << "packet " << p << "'s first byte";
    for (size_t k = 1; k < b->expect[p].size(); ++k)
      ASSERT_EQ(b->out_edge[byte + k], first + k) << "packet " << p << ": a gap";
    byte += b->expect[p].size();
    if (c + 1 < b->cmds.size()) {
      EXPECT_EQ(b->cmd_edge[c + 1], b->out_edge[byte - 1] + 1) << "command " << c + 1;
    }
    after_packet[c + 1] = true;
  }
  for (size_t i = 1; i < b->cmds.size(); ++i) {
    if (!after_packet[i]) {
      ASSERT_EQ(b->cmd_edge[i], b->cmd_edge[i - 1] + 1) << "command " << i;
    }
  }
}

}  // namespace
