// hls/spike_encoder.h: spike windows -> 5-byte link events. The test decodes
// the bytes itself from the documented layout (dt u16 LE, layer u8, neuron
// u16 LE; docs/protocol.md SPIKES), not through the kernel.
#include "hls/spike_encoder.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <tuple>
#include <vector>

namespace {

using Ev = std::tuple<unsigned, unsigned, unsigned>;  // dt, layer, neuron

std::vector<Ev> decode(const uint8_t* b, int n) {
  std::vector<Ev> e;
  for (int i = 0; i < n; ++i, b += 5)
    e.emplace_back(b[0] | b[1] << 8, b[2], b[3] | b[4] << 8);
  return e;
}

// Bound: every spike of a window, in order, with dt = t_frame - t_window
// (mod 2^16) and its layer and neuron; windows restart at the next frame.
TEST(SpikeEncoderHls, WindowsCarryEverySpikeWithItsOffset) {
  eskin::hls::SpikeEncoder<64> enc;
  std::mt19937 rng(5);
  uint32_t t = 0xFFFFFF00u;  // the sample counter wraps inside a window
  for (int w = 0; w < 50; ++w) {
    std::vector<Ev> want;
    const uint32_t t0 = t;
    for (int f = 0; f < 5; ++f, t += 35) {
      enc.frame(t);
      for (int s = 0; s < int(rng() % 4); ++s) {
        const unsigned layer = rng() % 2, neuron = rng() % 1024;
        enc.spike(uint8_t(layer), uint16_t(neuron));
        want.emplace_back((t - t0) & 0xFFFF, layer, neuron);
      }
    }
    uint32_t tw = 0;
    const int n = enc.close(tw);
    EXPECT_EQ(tw, t0);
    ASSERT_EQ(size_t(n), want.size());
    EXPECT_EQ(decode(enc.events(), n), want);
  }
  EXPECT_EQ(enc.dropped(), 0u);
}

// Bound: at most MAX events per window; each spike beyond is dropped and
// counted, the first MAX are kept intact.
TEST(SpikeEncoderHls, OverflowingAWindowDropsAndCounts) {
  eskin::hls::SpikeEncoder<4> enc;
  enc.frame(100);
  for (int i = 0; i < 7; ++i) enc.spike(0, uint16_t(i));
  uint32_t tw = 0;
  ASSERT_EQ(enc.close(tw), 4);
  EXPECT_EQ(enc.dropped(), 3u);
  EXPECT_EQ(decode(enc.events(), 4),
            (std::vector<Ev>{{0, 0, 0}, {0, 0, 1}, {0, 0, 2}, {0, 0, 3}}));
  enc.frame(200);  // a new window starts empty
  enc.spike(1, 9);
  ASSERT_EQ(enc.close(tw), 1);
  EXPECT_EQ(tw, 200u);
}

// The drop count is the STATUS packet's spikes_dropped field (u16,
// docs/protocol.md section 4: counters saturate at 0xFFFF), the rule of the
// microcode's SPKDROP: 65535 drops and more read 65535, in one window or
// over many, and stay there.
TEST(SpikeEncoderHls, DropCountSaturatesAtTheStatusFieldsFullScale) {
  eskin::hls::SpikeEncoder<1> enc;
  uint32_t tw = 0;
  enc.frame(0);
  for (int i = 0; i < 65535; ++i) enc.spike(0, 0);  // 1 kept, 65534 dropped
  EXPECT_EQ(enc.dropped(), 65534u);
  enc.spike(0, 1);
  EXPECT_EQ(enc.dropped(), 65535u);
  enc.spike(0, 2);
  EXPECT_EQ(enc.dropped(), 65535u);
  ASSERT_EQ(enc.close(tw), 1);
  for (uint32_t w = 1; w <= 3; ++w) {  // later windows overflow too: still 65535
    enc.frame(100 * w);
    for (int i = 0; i < 10; ++i) enc.spike(1, uint16_t(i));
    ASSERT_EQ(enc.close(tw), 1);
    EXPECT_EQ(tw, 100 * w);
    EXPECT_EQ(enc.dropped(), 65535u);
  }
}

}  // namespace

// close_packet: the SPIKES packet as docs/protocol.md lays it out (bytes
// written by hand): t = the window's first frame, 5 bytes an event; an
// empty window makes none.
TEST(SpikeEncoderHls, ClosePacketIsTheProtocolsSpikesPacket) {
  struct Packet {
    uint8_t type = 0;
    uint32_t t = 0;
    uint16_t len = 0;
    uint8_t payload[4 * eskin::hls::kSpikeEventBytes] = {};
  } p;
  eskin::hls::SpikeEncoder<4> enc;
  enc.frame(0x0001FFF0u);
  enc.spike(0, 0x0102);
  enc.frame(0x00020005u);  // dt = 0x15 (the window stays open)
  enc.spike(1, 7);
  ASSERT_TRUE(enc.close_packet(p));
  EXPECT_EQ(p.type, 0x04);
  EXPECT_EQ(p.t, 0x0001FFF0u);
  ASSERT_EQ(p.len, 10);
  const uint8_t want[10] = {0, 0, 0, 0x02, 0x01, 0x15, 0, 1, 7, 0};
  for (int i = 0; i < 10; ++i) EXPECT_EQ(p.payload[i], want[i]) << "byte " << i;
  enc.frame(9);
  EXPECT_FALSE(enc.close_packet(p));
}
