// rtl/cmd_decoder.v behind rtl/uart_rx.v, fed with frames from the host
// encoder (host/link/link_encoder) on a bit-level serial line (3 Mbaud at
// 12 MHz, CPB = 4). The decoder only checks framing (the frame engine judges
// contents, tests/rtl/dtmf_top_test.cpp), so the bounds here are:
//  * every well-formed frame comes out of the FIFO exactly as type, seq,
//    len (LE), payload — the t and CRC bytes removed — in arrival order;
//  * a flipped bit anywhere in the raw frame fails the CRC (CRC-16 finds
//    every single-bit error) or, in the length field, the structure check:
//    dropped, counted, nothing enqueued; truncated frames, a COBS block cut
//    short and a UART framing error inside a frame count as frame errors;
//  * a frame that does not fit the FIFO is dropped whole and counted as an
//    overflow (32-byte build), the frames before it are intact, and once the
//    reader drains the FIFO the next frame fits again;
//  * routed builds (rtl/mixed_top.v's two decoders on one line): every
//    command reaches exactly one of them, whole and in order, a type the
//    other owns is dropped without being counted, and a broken frame is
//    counted by both;
//  * `clear` zeroes the counters. Expected counts are counted by the test
//    from what it sent, never read back from the RTL.
//  * The cycle level's C++ models (sim/cycle/uart_rx.h feeding
//    sim/cycle/cmd_decoder.h) give the same avail, counters, frame_err and,
//    while avail, head as the RTL at every clock, on a line of good,
//    corrupt, cut and oversized frames with random pops and clears, in each
//    build (bound: exact).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "Vcmd_decoder_tb.h"
#include "Vcmd_decoder_tb_dtmf.h"
#include "Vcmd_decoder_tb_hall.h"
#include "Vcmd_decoder_tb_small.h"
#include "host/link/link_encoder.h"
#include "sim/cycle/cmd_decoder.h"
#include "sim/cycle/uart_rx.h"

using namespace eskin::link;

namespace {

constexpr int kCpb = 12000000 / 3000000;

template <class V>
struct Bench {
  std::unique_ptr<V> m = std::make_unique<V>();
  Bench() {
    m->clk = 0;
    m->rst = 1;
    m->rx = 1;
    m->pop = 0;
    m->clear = 0;
    for (int i = 0; i < 4; ++i) step(1);
    m->rst = 0;
  }
  void step(int level) {
    m->rx = uint8_t(level);
    m->clk = 1;
    m->eval();
    m->clk = 0;
    m->eval();
  }
  void send_byte(uint8_t b, int stop = 1) {
    for (int slot = 0; slot < 10; ++slot) {
      const int level = slot == 0 ? 0 : slot == 9 ? stop : (b >> (slot - 1)) & 1;
      for (int c = 0; c < kCpb; ++c) step(level);
    }
  }
  void send(const std::vector<uint8_t>& bytes) {
    for (uint8_t b : bytes) send_byte(b);
    for (int i = 0; i < 3 * kCpb; ++i) step(1);  // let the last byte land
  }
  // Everything the FIFO holds, read as the engine does: wait for avail,
  // sample head, pop.
  std::vector<uint8_t> drain() {
    std::vector<uint8_t> out;
    for (int idle = 0; idle < 8;) {
      if (!m->avail) {
        ++idle;
        step(1);
        continue;
      }
      idle = 0;
      out.push_back(m->head);
      m->pop = 1;
      step(1);
      m->pop = 0;
      step(1);
    }
    return out;
  }
};

// What the engine should read for a command: type, seq, len LE, payload.
std::vector<uint8_t> expected(uint8_t type, uint8_t seq, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> e(4 + payload.size());
  e[0] = type;
  e[1] = seq;
  e[2] = uint8_t(payload.size());
  e[3] = uint8_t(payload.size() >> 8);
  std::copy(payload.begin(), payload.end(), e.begin() + 4);
  return e;
}

TEST(CmdDecoder, WellFormedFramesComeOutWithoutTimeAndCrc) {
  Bench<Vcmd_decoder_tb> b;
  LinkEncoder enc;
  std::vector<uint8_t> want;
  const std::vector<std::vector<uint8_t>> payloads = {
      {}, {0x05}, {1, 2, 3}, {0, 0, 0, 0, 0}, std::vector<uint8_t>(300, 0xA5)};  // zeros: COBS
  for (size_t i = 0; i < payloads.size(); ++i) {
    const uint8_t type = uint8_t(0x81 + i), seq = enc.next_seq();
    b.send(enc.frame(type, 0x12345678u, payloads[i]));
    const auto e = expected(type, seq, payloads[i]);
    want.insert(want.end(), e.begin(), e.end());
  }
  EXPECT_EQ(b.drain(), want);
  EXPECT_EQ(b.m->crc_errors + b.m->frame_errors + b.m->overflows, 0);
}

TEST(CmdDecoder, CorruptFramesAreDroppedAndCounted) {
  Bench<Vcmd_decoder_tb> b;
  LinkEncoder enc;
  int crc = 0, frame = 0;
  const std::vector<uint8_t> payload = {3, 0x10, 0x27};
  const auto raw = raw_frame(0x82, 7, 0, payload);
  for (size_t bit = 0; bit < raw.size() * 8; ++bit) {
    auto r = raw;
    r[bit / 8] ^= uint8_t(1u << (bit % 8));
    auto wire = cobs_encode(r);
    wire.push_back(0);
    b.send(wire);
    // A flip in the len field breaks the structure check first.
    (bit / 8 == 6 || bit / 8 == 7) ? ++frame : ++crc;
  }
  auto wire = cobs_encode(raw);
  wire.push_back(0);
  auto cut = std::vector<uint8_t>(wire.begin(), wire.begin() + 6);
  cut.push_back(0);
  b.send(cut), ++frame;  // truncated (a COBS block cut short)
  auto shortf = cobs_encode(std::vector<uint8_t>(raw.begin(), raw.begin() + 8));
  shortf.push_back(0);
  b.send(shortf), ++frame;  // fewer than 10 raw bytes
  for (size_t i = 0; i < wire.size(); ++i) b.send_byte(wire[i], i == 3 ? 0 : 1);  // bad stop bit
  for (int i = 0; i < 3 * kCpb; ++i) b.step(1);
  ++frame;
  EXPECT_TRUE(b.drain().empty());
  EXPECT_EQ(b.m->crc_errors, crc);
  EXPECT_EQ(b.m->frame_errors, frame);
  const uint8_t seq = enc.next_seq();
  b.send(enc.frame(0x82, 0, payload));  // the stream goes on
  EXPECT_EQ(b.drain(), expected(0x82, seq, payload));
  b.m->clear = 1;
  b.step(1);
  b.m->clear = 0;
  EXPECT_EQ(b.m->crc_errors + b.m->frame_errors + b.m->overflows, 0);
}

TEST(CmdDecoder, AFrameThatDoesNotFitIsDroppedWhole) {
  Bench<Vcmd_decoder_tb_small> b;  // 32-byte FIFO
  LinkEncoder enc;
  const std::vector<uint8_t> p10(10, 0x11);  // 14 bytes in the FIFO each
  std::vector<uint8_t> want;
  for (int i = 0; i < 2; ++i) {
    const uint8_t seq = enc.next_seq();
    b.send(enc.frame(0x88, 0, p10));
    const auto e = expected(0x88, seq, p10);
    want.insert(want.end(), e.begin(), e.end());
  }
  b.send(enc.frame(0x88, 0, p10));  // 28 + 14 + 2 CRC > 32: dropped
  EXPECT_EQ(b.m->overflows, 1);
  EXPECT_EQ(b.drain(), want);
  const uint8_t seq = enc.next_seq();
  b.send(enc.frame(0x88, 0, p10));  // room again
  EXPECT_EQ(b.drain(), expected(0x88, seq, p10));
  EXPECT_EQ(b.m->overflows, 1);
  EXPECT_EQ(b.m->crc_errors + b.m->frame_errors, 0);
}

TEST(CmdDecoder, RoutedDecodersSplitTheLineByType) {
  Bench<Vcmd_decoder_tb_dtmf> d;  // all but 0x90-0x9F
  Bench<Vcmd_decoder_tb_hall> h;  // 0x90-0x9F only
  LinkEncoder enc;
  std::vector<uint8_t> want_d, want_h;
  // Both ends of the Hall range and their neighbours, interleaved.
  const uint8_t types[] = {0x84, 0x90, 0x8F, 0x99, 0x9F, 0xA0, 0x9C, 0x80, 0x86};
  for (uint8_t type : types) {
    const std::vector<uint8_t> payload = {type, 0x00, 0x5A};
    const uint8_t seq = enc.next_seq();
    const auto wire = enc.frame(type, 0, payload);
    d.send(wire);
    h.send(wire);
    const auto e = expected(type, seq, payload);
    auto& w = (type >= 0x90 && type <= 0x9F) ? want_h : want_d;
    w.insert(w.end(), e.begin(), e.end());
  }
  auto raw = raw_frame(0x99, 1, 0, {1, 2});
  raw[9] ^= 0x10;  // a CRC error: both decoders count it
  auto bad = cobs_encode(raw);
  bad.push_back(0);
  d.send(bad);
  h.send(bad);
  EXPECT_EQ(d.drain(), want_d);
  EXPECT_EQ(h.drain(), want_h);
  EXPECT_EQ(want_d.size(), 5u * 7u);  // 0x84 0x8F 0xA0 0x80 0x86
  EXPECT_EQ(want_h.size(), 4u * 7u);  // 0x90 0x99 0x9F 0x9C
  EXPECT_EQ(d.m->crc_errors, 1);
  EXPECT_EQ(h.m->crc_errors, 1);
  EXPECT_EQ(d.m->frame_errors + d.m->overflows + h.m->frame_errors + h.m->overflows, 0);
}

}  // namespace

namespace {

// A line of random command frames for the cycle models' comparison: good
// frames, a flipped bit, a frame cut short, a spoiled stop bit, frames too
// large for a small FIFO, at random gaps.
std::vector<uint8_t> command_line(int frames, uint64_t seed) {
  std::mt19937_64 rng(seed);
  LinkEncoder enc;
  std::vector<uint8_t> line(size_t(3 * kCpb), 1);
  const auto put = [&](uint8_t b, int stop) {
    for (int slot = 0; slot < 10; ++slot) {
      const int level = slot == 0 ? 0 : slot == 9 ? stop : (b >> (slot - 1)) & 1;
      line.insert(line.end(), size_t(kCpb), uint8_t(level));
    }
  };
  static const uint8_t kTypes[] = {0x81, 0x84, 0x8F, 0x90, 0x99, 0x9F, 0xA0};
  for (int f = 0; f < frames; ++f) {
    std::vector<uint8_t> payload(size_t(rng() % (rng() % 8 == 0 ? 40 : 8)));
    for (auto& x : payload) x = rng() % 3 == 0 ? 0 : uint8_t(rng());
    auto wire = enc.frame(kTypes[rng() % 7], uint32_t(rng()), payload);
    const int kind = int(rng() % 8);
    if (kind == 0) wire[1 + rng() % (wire.size() - 2)] ^= uint8_t(1u << (rng() % 8));
    if (kind == 1) wire.erase(wire.begin() + long(1 + rng() % (wire.size() - 2)), wire.end() - 1);
    const size_t spoil = kind == 2 ? rng() % wire.size() : wire.size();
    for (size_t i = 0; i < wire.size(); ++i) put(wire[i], i == spoil ? 0 : 1);
    if (kind == 2) line.insert(line.end(), size_t(kCpb), 1);
    line.insert(line.end(), size_t(rng() % 3 == 0 ? rng() % (20 * kCpb) : 0), 1);
  }
  line.insert(line.end(), size_t(40 * kCpb), 1);
  return line;
}

template <class V>
void same_as_model(eskin::cycle::CmdDecoder dec, double p_pop, bool overflows_expected,
                   uint64_t seed) {
  Bench<V> b;
  eskin::cycle::UartRx rx(12000000, 3000000);
  rx.reset();
  dec.reset();
  const auto line = command_line(300, seed);
  std::mt19937_64 rng(seed + 1);
  std::bernoulli_distribution pop(p_pop), clear(0.00002);
  long popped = 0, crc_seen = 0, frame_seen = 0, ovf_seen = 0;
  for (size_t c = 0; c < line.size(); ++c) {
    const bool p = pop(rng), cl = clear(rng);
    b.m->rx = line[c];
    b.m->pop = p;
    b.m->clear = cl;
    b.m->eval();
    ASSERT_EQ(bool(b.m->avail), dec.avail()) << "clock " << c;
    if (dec.avail()) {
      ASSERT_EQ(b.m->head, dec.head()) << "clock " << c;
    }
    ASSERT_EQ(b.m->crc_errors, dec.crc_errors()) << "clock " << c;
    ASSERT_EQ(b.m->frame_errors, dec.frame_errors()) << "clock " << c;
    ASSERT_EQ(b.m->overflows, dec.overflows()) << "clock " << c;
    ASSERT_EQ(bool(b.m->rx_frame_err), rx.frame_err()) << "clock " << c;
    popped += p && dec.avail();
    const uint16_t crc0 = dec.crc_errors(), fr0 = dec.frame_errors(), ov0 = dec.overflows();
    // The decoder takes the receiver's registered outputs of this clock.
    dec.clock(rx.m_valid(), rx.m_data(), rx.frame_err() || rx.overrun(), p, cl);
    rx.clock(line[c] != 0, true);
    crc_seen += dec.crc_errors() > crc0;
    frame_seen += dec.frame_errors() > fr0;
    ovf_seen += dec.overflows() > ov0;
    b.m->clk = 1; b.m->eval(); b.m->clk = 0; b.m->eval();
  }
  // The line reached every path: reads, each kind of error, clears.
  EXPECT_GT(popped, 100) << "the drive must read commands out";
  EXPECT_GT(crc_seen, 5);
  EXPECT_GT(frame_seen, 5);
  EXPECT_EQ(ovf_seen > 0, overflows_expected);
}

}  // namespace

TEST(CmdDecoder, CycleModelEqualsTheRtlEveryClock) {
  using eskin::cycle::CmdDecoder;
  same_as_model<Vcmd_decoder_tb>(CmdDecoder(512), 0.05, false, 41);
  same_as_model<Vcmd_decoder_tb_small>(CmdDecoder(32), 0.002, true, 42);
  same_as_model<Vcmd_decoder_tb_dtmf>(CmdDecoder(512, 0x90, 0x9F, false), 0.05, false, 43);
  same_as_model<Vcmd_decoder_tb_hall>(CmdDecoder(512, 0x90, 0x9F, true), 0.05, false, 44);
}
