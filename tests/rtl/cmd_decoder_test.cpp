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
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "Vcmd_decoder_tb.h"
#include "Vcmd_decoder_tb_dtmf.h"
#include "Vcmd_decoder_tb_hall.h"
#include "Vcmd_decoder_tb_small.h"
#include "host/link/link_encoder.h"

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
