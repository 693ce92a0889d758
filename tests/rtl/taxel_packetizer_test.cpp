// rtl/taxel_packetizer.v against hls/taxel_packetizer.h (TaxelPacketizer::frame
// and fifo_bytes, the packets hls/dtmf_chain.h sends), byte for byte, at the
// 3x3 default (Vtaxel_packetizer) and at 64x64 (Vtaxel_packetizer_64,
// taxel_packetizer_test.cmake).
//
// Bound: exact. The block only moves bytes, so its output must be the
// kernel's FIFO bytes of every frame's packets, in order. Checked:
//   - random frames (values around the sparse threshold, zeros, 0xFFFF; all
//     four dense/sparse choices; sparse_min 0, 1 and random) with random
//     header, taxel and out_ready timing (seeded); out_data holds while
//     the output stalls; plus frames with no taxel lit (sparse len 0) and
//     every taxel lit (4T);
//   - whole packets or none: into a modelled FIFO of a few packets that
//     drains slowly (out_free from it): the FIFO never overflows, the bytes
//     parse into the kernel's packets in order with some left out, each
//     left-out packet pulsed `dropped` once, at a clock when out_free could
//     not hold it;
//   - timing with every stream ready, in handshake edges: one byte a clock
//     inside a packet; the dense packet's first byte 2 edges after its
//     frame's header; taxel k of a dense frame 10 + 2k edges after the
//     header, a taxel a clock without a dense packet; the sparse packet's
//     first byte 2 edges after the dense packet's last (3 after the last
//     taxel without one); the next header 1 edge after the last byte (2
//     after the last taxel of a frame with no packet).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "Vtaxel_packetizer.h"
#include "Vtaxel_packetizer_64.h"
#include "clocked_dut.h"
#include "hls/taxel_packetizer.h"

namespace {

namespace hls = eskin::hls;
using Bytes = std::vector<uint8_t>;

struct FrameIn {
  uint32_t t = 0;
  bool dense = false, sparse = false;
  uint16_t sparse_min = 0;
  std::vector<uint16_t> g;
};

// One expected packet: its FIFO bytes and which frame made it.
struct Expected {
  Bytes bytes;
  size_t frame = 0;
};

template <class V, int R, int C>
struct Bench : ClockedDut<V> {
  static constexpr int kR = R, kC = C, kT = R * C;
  using K = hls::TaxelPacketizer<R, C>;
  using ClockedDut<V>::m;
  using ClockedDut<V>::cycle;
  using ClockedDut<V>::tick;

  struct Packet {
    uint8_t type = 0;
    uint32_t t = 0;
    uint16_t len = 0;
    uint8_t payload[K::kSparseMaxLen > K::kDenseLen ? K::kSparseMaxLen : K::kDenseLen] = {};
  };

  std::mt19937 rng;
  double p_hdr = 1.0, p_in = 1.0, p_out = 1.0;
  int fifo_depth = 0;        // > 0: out_free from a FIFO of this size
  double p_drain = 1.0;      // its reader's chance to take a byte a clock
  std::vector<FrameIn> frames;
  std::vector<Expected> expect;

  // Observed.
  Bytes out;
  std::vector<uint64_t> out_edge;   // edge each byte was taken at
  std::vector<uint64_t> hdr_edge;   // per frame: its header's handshake edge
  std::vector<std::vector<uint64_t>> in_edge;  // per frame, per taxel
  std::vector<int64_t> drop_free;  // per dropped pulse: out_free - out_valid at its decision
  size_t fifo_used = 0, fifo_peak = 0;
  bool overflow = false;

  explicit Bench(uint32_t seed) : rng(seed) {
    m.hdr_valid = 0;
    m.out_free = 0xFFFF;
    this->reset();
  }

  void add(const FrameIn& f) {
    frames.push_back(f);
    Packet p[2];
    const int n = K::frame(f.g.data(), f.t, f.dense, f.sparse, f.sparse_min, p);
    for (int i = 0; i < n; ++i) {
      Expected e;
      e.frame = frames.size() - 1;
      e.bytes.resize(size_t(K::kHeaderBytes + p[i].len));
      EXPECT_EQ(K::fifo_bytes(p[i], e.bytes.data()), int(e.bytes.size()));
      expect.push_back(e);
    }
  }

  bool coin(double p) { return p >= 1.0 || std::uniform_real_distribution<double>(0, 1)(rng) < p; }

  size_t expected_bytes() const {
    size_t n = 0;
    for (const auto& e : expect) n += e.bytes.size();
    return n;
  }

  // Runs until every frame's taxels are in and the block is idle again.
  void run() {
    size_t next_hdr = 0, fi = 0;
    int next_tax = 0;
    bool held = false;
    uint8_t held_data = 0;
    in_edge.assign(frames.size(), {});
    const uint64_t deadline = cycle + 200 * (frames.size() * kT + expected_bytes()) + 1000;
    while (cycle < deadline) {
      const bool taxels_done = next_hdr == frames.size() && fi == frames.size();
      if (taxels_done && m.idle && !m.out_valid) break;
      m.hdr_valid = next_hdr < frames.size() && next_hdr == fi && coin(p_hdr);
      if (m.hdr_valid) {
        const FrameIn& f = frames[next_hdr];
        m.hdr_t = f.t;
        m.hdr_dense = f.dense;
        m.hdr_sparse = f.sparse;
        m.hdr_sparse_min = f.sparse_min;
      }
      // Taxels of the frame whose header was taken.
      m.in_valid = fi < next_hdr && coin(p_in);
      if (m.in_valid) {
        m.in_value = frames[fi].g[size_t(next_tax)];
        m.in_row = uint8_t(next_tax / C);
        m.in_col = uint8_t(next_tax % C);
        m.in_last = next_tax == kT - 1;
      }
      if (fifo_depth > 0) {
        m.out_free = uint16_t(fifo_depth - int(fifo_used));
        m.out_ready = 1;
      } else {
        m.out_ready = coin(p_out);
      }
      m.eval();
      if (held) {
        EXPECT_TRUE(m.out_valid) << "byte withdrawn while stalled, byte " << out.size();
        EXPECT_EQ(m.out_data, held_data) << "out_data changed while stalled, byte " << out.size();
      }
      const bool hdr_take = m.hdr_valid && m.hdr_ready;
      const bool in_take = m.in_valid && m.in_ready;
      const bool out_take = m.out_valid && m.out_ready;
      if (out_take) {
        out.push_back(m.out_data);
        out_edge.push_back(cycle + 1);
      }
      held = m.out_valid && !m.out_ready;
      held_data = m.out_data;
      const int64_t room = int64_t(m.out_free) - (m.out_valid ? 1 : 0);
      tick();
      if (m.dropped) drop_free.push_back(room);  // decided at the edge just taken
      if (hdr_take) hdr_edge.push_back(cycle), ++next_hdr, next_tax = 0;
      if (in_take) {
        in_edge[fi].push_back(cycle);
        if (++next_tax == kT) ++fi, next_tax = 0;
      }
      if (fifo_depth > 0) {
        if (out_take) {
          if (fifo_used == size_t(fifo_depth)) overflow = true;
          else ++fifo_used;
        }
        fifo_peak = std::max(fifo_peak, fifo_used);
        if (fifo_used > 0 && coin(p_drain)) --fifo_used;
      }
    }
    ASSERT_LT(cycle, deadline) << "the block did not finish: " << out.size() << " of "
                               << expected_bytes() << " bytes";
  }

  void check_exact() {
    Bytes want;
    for (const auto& e : expect) want.insert(want.end(), e.bytes.begin(), e.bytes.end());
    ASSERT_EQ(out.size(), want.size()) << "byte count";
    size_t at = 0;
    for (const auto& e : expect) {
      for (size_t b = 0; b < e.bytes.size(); ++b)
        ASSERT_EQ(out[at + b], e.bytes[b])
            << "frame " << e.frame << ", packet type " << int(e.bytes[0]) << ", byte " << b;
      at += e.bytes.size();
    }
  }
};

using B3 = Bench<Vtaxel_packetizer, 3, 3>;
using B64 = Bench<Vtaxel_packetizer_64, 64, 64>;

// Values around a threshold `lo`, zeros and the extremes.
FrameIn random_frame(int t_count, uint32_t t, std::mt19937& rng, int kind) {
  FrameIn f;
  f.t = t;
  f.dense = (kind & 1) != 0;
  f.sparse = (kind & 2) != 0;
  const int pick = int(rng() % 4);
  f.sparse_min = pick == 0 ? 0 : pick == 1 ? 1 : uint16_t(rng() % 3000);
  f.g.resize(size_t(t_count));
  for (auto& v : f.g) {
    switch (rng() % 6) {
      case 0: v = 0; break;
      case 1: v = 0xFFFF; break;
      case 2: v = uint16_t(f.sparse_min + int(rng() % 3) - 1); break;  // lo - 1 .. lo + 1
      case 3: v = 1; break;
      default: v = uint16_t(rng()); break;
    }
  }
  return f;
}

template <class B>
void random_frames(uint32_t seed, int frames, double p_hdr, double p_in, double p_out) {
  std::mt19937 rng(seed);
  B b(seed + 100);
  b.p_hdr = p_hdr;
  b.p_in = p_in;
  b.p_out = p_out;
  for (int f = 0; f < frames; ++f) b.add(random_frame(B::kT, uint32_t(rng()), rng, f % 4));
  // No taxel lit (sparse len 0) and every one lit, with both packets.
  FrameIn dark{uint32_t(rng()), true, true, 0, std::vector<uint16_t>(size_t(B::kT), 0)};
  FrameIn lit{uint32_t(rng()), true, true, 1, std::vector<uint16_t>(size_t(B::kT), 0x8001)};
  b.add(dark);
  b.add(lit);
  b.run();
  ASSERT_TRUE(b.drop_free.empty()) << "a packet dropped with room";
  b.check_exact();
}

TEST(TaxelPacketizer, Default3x3ByteExactUnderRandomValidAndBackPressure) {
  random_frames<B3>(1, 400, 0.5, 0.6, 0.5);
  random_frames<B3>(2, 400, 0.9, 0.9, 0.2);
  random_frames<B3>(3, 400, 0.3, 0.3, 0.95);
}

TEST(TaxelPacketizer, Skin64x64ByteExactUnderRandomValidAndBackPressure) {
  random_frames<B64>(4, 8, 0.5, 0.6, 0.5);
  random_frames<B64>(5, 4, 0.9, 0.95, 0.3);
}

// A FIFO that drains slower than the packets come: packets are left out
// whole, and only when they would not fit.
template <class B>
void whole_or_none(uint32_t seed, int frames, int depth, double p_drain) {
  std::mt19937 rng(seed);
  B b(seed + 200);
  b.p_hdr = 0.8;
  b.p_in = 0.8;
  b.fifo_depth = depth;
  b.p_drain = p_drain;
  for (int f = 0; f < frames; ++f) b.add(random_frame(B::kT, uint32_t(rng()), rng, 3));
  b.run();
  EXPECT_FALSE(b.overflow) << "a byte written into a full FIFO";
  EXPECT_LE(b.fifo_peak, size_t(depth));
  // Parse the bytes into packets and match them in order against the
  // kernel's, some left out.
  size_t at = 0, e = 0, sent = 0;
  std::vector<size_t> dropped_lens;
  while (at < b.out.size()) {
    ASSERT_GE(b.out.size() - at, 7u) << "a cut packet at byte " << at;
    const size_t len = b.out[at + 5] | size_t(b.out[at + 6]) << 8;
    ASSERT_GE(b.out.size() - at, 7 + len) << "a cut packet at byte " << at;
    const Bytes got(b.out.begin() + long(at), b.out.begin() + long(at + 7 + len));
    while (e < b.expect.size() && b.expect[e].bytes != got) dropped_lens.push_back(b.expect[e++].bytes.size());
    ASSERT_LT(e, b.expect.size()) << "packet at byte " << at << " is none of the kernel's";
    ++e, ++sent, at += 7 + len;
  }
  while (e < b.expect.size()) dropped_lens.push_back(b.expect[e++].bytes.size());
  ASSERT_EQ(b.drop_free.size(), dropped_lens.size()) << "dropped pulses vs packets left out";
  for (size_t i = 0; i < dropped_lens.size(); ++i)
    EXPECT_LT(b.drop_free[i], int64_t(dropped_lens[i])) << "packet " << i << " dropped with room for it";
  EXPECT_GT(sent, 0u);
  EXPECT_GT(dropped_lens.size(), 0u) << "the FIFO never filled: nothing tested";
  std::printf("%zu packets sent, %zu left out, FIFO peak %zu of %d bytes\n", sent,
              dropped_lens.size(), b.fifo_peak, depth);
}

TEST(TaxelPacketizer, Default3x3WholePacketsOrNoneIntoASlowFifo) {
  whole_or_none<B3>(6, 600, 64, 0.9);
}

TEST(TaxelPacketizer, Skin64x64WholePacketsOrNoneIntoASlowFifo) {
  whole_or_none<B64>(7, 8, 16384, 0.4);
}

// The room rule at its edge, into a FIFO nobody reads: a packet goes in
// when the FIFO holds exactly its 7 + len bytes, and is left out at one
// byte less. The sparse packet's check comes while the dense packet's last
// byte still waits in out_data (counted against the room).
TEST(TaxelPacketizer, Default3x3RoomRuleAtTheByte) {
  FrameIn f{0x01020304u, true, true, 100, {0, 100, 99, 7, 0xFFFF, 0, 0, 0, 0}};
  constexpr int kDense = 7 + 2 + 18, kSparse = 7 + 8;  // 2 taxels listed
  struct Case {
    int depth;
    bool dense, sparse;
  };
  for (const Case c : {Case{kDense + kSparse, true, true}, Case{kDense + kSparse - 1, true, false},
                       Case{kDense - 1, false, true}, Case{kSparse - 1, false, false}}) {
    B3 b(11);
    b.fifo_depth = c.depth;
    b.p_drain = 0;
    b.add(f);
    b.run();
    ASSERT_EQ(b.expect.size(), 2u);
    Bytes want;
    if (c.dense) want = b.expect[0].bytes;
    if (c.sparse) want.insert(want.end(), b.expect[1].bytes.begin(), b.expect[1].bytes.end());
    EXPECT_EQ(b.out, want) << "FIFO of " << c.depth << " bytes";
    EXPECT_EQ(b.drop_free.size(), size_t(!c.dense) + size_t(!c.sparse)) << "FIFO of " << c.depth;
    EXPECT_FALSE(b.overflow);
  }
}

template <class B>
void exact_timing(uint32_t seed, int frames) {
  std::mt19937 rng(seed);
  B b(seed + 300);
  for (int f = 0; f < frames; ++f) b.add(random_frame(B::kT, uint32_t(rng()), rng, f % 4));
  b.run();
  b.check_exact();
  ASSERT_EQ(b.hdr_edge.size(), size_t(frames));
  size_t byte = 0, e = 0;
  uint64_t next_hdr = 0;  // the edge the next header must be taken at
  for (size_t f = 0; f < size_t(frames); ++f) {
    const auto& in = b.in_edge[f];
    ASSERT_EQ(in.size(), size_t(B::kT));
    if (f > 0) {
      EXPECT_EQ(b.hdr_edge[f], next_hdr) << "frame " << f << "'s header";
    }
    uint64_t prev = 0;  // the dense packet's last byte's handshake edge
    bool dense_sent = false, any = false;
    for (; e < b.expect.size() && b.expect[e].frame == f; ++e) {
      const size_t n = b.expect[e].bytes.size();
      const uint64_t first = b.out_edge[byte];
      if (b.expect[e].bytes[0] == hls::kDtmfTaxelsDense) {
        dense_sent = true;
        EXPECT_EQ(first, b.hdr_edge[f] + 2) << "frame " << f << ": dense packet's first byte";
        for (int k = 0; k < B::kT; ++k) {
          ASSERT_EQ(in[size_t(k)], b.hdr_edge[f] + 10 + 2 * uint64_t(k))
              << "frame " << f << " taxel " << k;
        }
      } else {
        const uint64_t want = dense_sent ? prev + 2 : in.back() + 3;
        EXPECT_EQ(first, want) << "frame " << f << ": sparse packet's first byte";
      }
      for (size_t k = 1; k < n; ++k)
        ASSERT_EQ(b.out_edge[byte + k], first + k) << "frame " << f << ": a gap inside a packet";
      byte += n;
      prev = b.out_edge[byte - 1];
      any = true;
    }
    if (!dense_sent) {
      for (int k = 1; k < B::kT; ++k)
        ASSERT_EQ(in[size_t(k)], in[0] + uint64_t(k)) << "frame " << f << " taxel " << k;
    }
    next_hdr = any ? prev + 1 : in.back() + 2;
  }
}

TEST(TaxelPacketizer, Default3x3ExactTimingOneByteAClock) { exact_timing<B3>(8, 40); }

TEST(TaxelPacketizer, Skin64x64ExactTimingOneByteAClock) { exact_timing<B64>(9, 4); }

}  // namespace
