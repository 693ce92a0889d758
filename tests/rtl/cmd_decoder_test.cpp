// rtl/cmd_decoder.v behind rtl/uart_rx.v, fed with frames from the host
// encoder (host/link/link_encoder) on a bit-level serial line (3 Mbaud at
// 12 MHz, CPB = 4).
//
// Bounds and why (docs/protocol.md is the spec):
//  * Every valid command is applied exactly: the register equals the
//    commanded value, accepted counts it, cfg_changed pulses once.
//  * Every out-of-range command (each documented limit, on both sides of
//    the boundary where there is one) is rejected with its documented
//    reason code, type and sequence number, leaves every register as it
//    was, and pulses status_req once (a status packet reports it).
//  * Frames with a flipped bit in the raw frame fail the CRC (CRC-16 finds
//    every single-bit error: x^i is no multiple of the generator) or, in the
//    length field, the structure check; either way they are dropped,
//    counted (crc_errors / frame_errors), and nothing changes. Truncated
//    frames, a COBS block cut short, a UART framing error inside a frame:
//    frame_errors. After all of that the next valid command still applies.
//  * Counters: the expected values are counted by the test from what it
//    sent, not read back from the RTL.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "Vcmd_decoder_tb.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"

using namespace eskin::link;

namespace {

constexpr int kCpb = 12000000 / 3000000;

struct Bench {
  std::unique_ptr<Vcmd_decoder_tb> m = std::make_unique<Vcmd_decoder_tb>();
  int cfg_pulses = 0, status_pulses = 0;
  Bench() {
    m->clk = 0; m->rst = 1; m->rx = 1;
    for (int i = 0; i < 4; ++i) step(1);
    m->rst = 0;
  }
  void step(int level) {
    m->rx = uint8_t(level);
    m->clk = 1; m->eval();
    m->clk = 0; m->eval();
    cfg_pulses += m->cfg_changed;
    status_pulses += m->status_req;
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
  uint32_t inc(int k) const { return m->carrier_inc[k]; }
  uint16_t thr(int id) const { return uint16_t(m->thresholds >> (16 * id)); }
  int32_t neuron(int id) const { return int32_t(m->neuron[id]); }
  uint16_t decim(int s) const { return uint16_t(m->decim >> (16 * s)); }
};

// Snapshot of every register, to show a rejected or dropped frame changes nothing.
struct Regs {
  uint32_t inc[6]; uint64_t thr; uint32_t neuron[4]; uint8_t mask; uint64_t decim;
  explicit Regs(const Bench& b) {
    for (int k = 0; k < 6; ++k) inc[k] = b.inc(k);
    thr = b.m->thresholds;
    for (int i = 0; i < 4; ++i) neuron[i] = uint32_t(b.neuron(i));
    mask = b.m->out_mask; decim = b.m->decim;
  }
  bool operator==(const Regs& o) const {
    for (int k = 0; k < 6; ++k) if (inc[k] != o.inc[k]) return false;
    for (int i = 0; i < 4; ++i) if (neuron[i] != o.neuron[i]) return false;
    return thr == o.thr && mask == o.mask && decim == o.decim;
  }
};

constexpr int32_t kMv = 1 << 22;  // 1 mV in Q9.22

}  // namespace

TEST(CmdDecoder, ValidCommandsAreApplied) {
  Bench b;
  LinkEncoder enc;
  int n = 0;
  for (int k = 0; k < 6; ++k) { b.send(enc.set_carrier_inc(uint8_t(k), 0x01000000u * (k + 1) + 7)); ++n; }
  b.send(enc.set_carrier_inc(5, 0x7FFFFFFF)); ++n;   // just below Nyquist
  b.send(enc.set_carrier_inc(4, 1)); ++n;            // smallest
  for (int id = 0; id < 4; ++id) { b.send(enc.set_threshold(uint8_t(id), uint16_t(1000 * id + 1))); ++n; }
  b.send(enc.set_neuron(0, -60 * kMv)); ++n;
  b.send(enc.set_output_mask(0x05)); ++n;
  b.send(enc.set_decimation(0, 1)); ++n;
  b.send(enc.set_decimation(1, 0xFFFF)); ++n;
  b.send(enc.set_decimation(2, 350)); ++n;
  for (int k = 0; k < 4; ++k) EXPECT_EQ(b.inc(k), 0x01000000u * (k + 1) + 7) << k;
  EXPECT_EQ(b.inc(4), 1u);
  EXPECT_EQ(b.inc(5), 0x7FFFFFFFu);
  for (int id = 0; id < 4; ++id) EXPECT_EQ(b.thr(id), 1000 * id + 1);
  EXPECT_EQ(b.neuron(0), -60 * kMv);
  EXPECT_EQ(b.m->out_mask, 0x05);
  EXPECT_EQ(b.decim(0), 1); EXPECT_EQ(b.decim(1), 0xFFFF); EXPECT_EQ(b.decim(2), 350);
  EXPECT_EQ(b.m->accepted, n);
  EXPECT_EQ(b.cfg_pulses, n);
  EXPECT_EQ(b.m->rejected + b.m->crc_errors + b.m->frame_errors, 0);
  EXPECT_EQ(b.status_pulses, 0);
}

TEST(CmdDecoder, NeuronParametersAtTheirLimits) {
  Bench b;
  LinkEncoder enc;
  auto neuron = [&](uint8_t id, int32_t v) { return enc.set_neuron(id, v); };
  struct Case { uint8_t id; int32_t v; bool ok; };
  const Case cases[] = {
      {0, -128 * kMv, true}, {0, 30 * kMv - 1, true}, {0, 30 * kMv, false},
      {0, -128 * kMv - 1, false}, {0, -55 * kMv, true},
      {1, 0, true}, {1, (1 << 30) - 1, true}, {1, -1, false}, {1, 1 << 30, false},
      {2, -32768, true}, {2, 32767, true}, {2, 32768, false}, {2, -32769, false},
      {3, 0, true}, {3, 31, true}, {3, 32, false}, {3, -1, false},
      {4, 0, false},  // no such parameter
  };
  int32_t want[4] = {b.neuron(0), b.neuron(1), b.neuron(2), b.neuron(3)};
  int acc = 0, rej = 0;
  for (const Case& c : cases) {
    const uint8_t seq = enc.next_seq();
    b.send(neuron(c.id, c.v));
    if (c.ok) {
      want[c.id] = c.v;
      ++acc;
    } else {
      ++rej;
      EXPECT_EQ(b.m->last_reject_type, kCmdSetNeuron);
      EXPECT_EQ(b.m->last_reject_reason, c.id >= 4 ? kRejectBadIndex : kRejectBadValue)
          << "id " << int(c.id) << " value " << c.v;
      EXPECT_EQ(b.m->last_reject_seq, seq);
    }
    for (int i = 0; i < 4; ++i) ASSERT_EQ(b.neuron(i), want[i]) << "id " << int(c.id) << " v " << c.v;
  }
  EXPECT_EQ(b.m->accepted, acc);
  EXPECT_EQ(b.m->rejected, rej);
  EXPECT_EQ(b.status_pulses, rej);
}

TEST(CmdDecoder, OutOfRangeCommandsAreRejectedWithReason) {
  Bench b;
  LinkEncoder enc;
  struct Case { std::vector<uint8_t> frame; uint8_t type, reason, seq; };
  std::vector<Case> cases;
  auto add = [&](uint8_t type, uint8_t reason, std::vector<uint8_t> f) {
    cases.push_back({std::move(f), type, reason, uint8_t(enc.next_seq() - 1)});
  };
  add(kCmdSetCarrierInc, kRejectBadIndex, enc.set_carrier_inc(6, 1000));
  add(kCmdSetCarrierInc, kRejectBadValue, enc.set_carrier_inc(0, 0));
  add(kCmdSetCarrierInc, kRejectBadValue, enc.set_carrier_inc(0, 0x80000000u));
  add(kCmdSetThreshold, kRejectBadIndex, enc.set_threshold(4, 1));
  add(kCmdSetOutputMask, kRejectReservedBits, enc.set_output_mask(0x10));
  add(kCmdSetOutputMask, kRejectReservedBits, enc.set_output_mask(0x8F));
  add(kCmdSetDecimation, kRejectBadValue, enc.set_decimation(0, 0));
  add(kCmdSetDecimation, kRejectBadIndex, enc.set_decimation(3, 10));
  add(0x99, kRejectUnknownType, enc.frame(0x99, 0, {1, 2}));
  add(0x05, kRejectUnknownType, enc.frame(kStatus, 0, std::vector<uint8_t>(24, 0)));
  add(kCmdSetOutputMask, kRejectBadLength, enc.frame(kCmdSetOutputMask, 0, {1, 0}));
  add(kCmdSetCarrierInc, kRejectBadLength, enc.frame(kCmdSetCarrierInc, 0, {0, 1, 2, 3}));
  add(kCmdRequestStatus, kRejectBadLength, enc.frame(kCmdRequestStatus, 0, {0}));
  add(kCmdSetThreshold, kRejectBadLength, enc.frame(kCmdSetThreshold, 0, std::vector<uint8_t>(300, 7)));
  const Regs before(b);
  int n = 0;
  for (const Case& c : cases) {
    b.send(c.frame);
    ++n;
    EXPECT_EQ(b.m->rejected, n);
    EXPECT_EQ(b.m->last_reject_type, c.type) << "case " << n;
    EXPECT_EQ(b.m->last_reject_reason, c.reason) << "case " << n;
    EXPECT_EQ(b.m->last_reject_seq, c.seq) << "case " << n;
    EXPECT_EQ(b.status_pulses, n);
    EXPECT_TRUE(Regs(b) == before) << "case " << n << " changed a register";
  }
  EXPECT_EQ(b.m->accepted, 0);
  EXPECT_EQ(b.cfg_pulses, 0);
  // REQUEST_STATUS pulses status_req; CLEAR_COUNTERS zeroes the counters.
  b.send(enc.request_status());
  EXPECT_EQ(b.status_pulses, n + 1);
  EXPECT_EQ(b.m->accepted, 1);
  b.send(enc.clear_counters());
  EXPECT_EQ(b.m->rejected + b.m->accepted + b.m->last_reject_type + b.m->last_reject_reason, 0);
}

TEST(CmdDecoder, CorruptFramesAreDroppedAndCounted) {
  Bench b;
  LinkEncoder enc;
  b.send(enc.set_output_mask(0x03));
  const Regs before(b);
  // Every single-bit flip of a raw SET_DECIMATION frame, re-encoded with COBS.
  const auto raw = raw_frame(kCmdSetDecimation, 42, 0, {0, 0x10, 0x00});
  int crc = 0, framing = 0;
  for (size_t bit = 0; bit < raw.size() * 8; ++bit) {
    auto bad = raw;
    bad[bit / 8] ^= uint8_t(1u << (bit % 8));
    auto wire = cobs_encode(bad);
    wire.push_back(0);
    b.send(wire);
    if (bit / 8 == 6 || bit / 8 == 7) ++framing; else ++crc;  // len field -> structure
  }
  // Truncated frames (cut anywhere, then a delimiter), and a COBS block cut short.
  const auto good = enc.set_decimation(1, 77);
  for (size_t cut = 1; cut + 1 < good.size(); ++cut) {
    std::vector<uint8_t> t(good.begin(), good.begin() + long(cut));
    t.push_back(0);
    b.send(t);
    ++framing;
  }
  b.send({0x09, 0x81, 0x00});  // code says 8 data bytes, delimiter after 1
  ++framing;
  // A UART framing error (stop bit 0) on a byte inside an otherwise good frame.
  const auto f = enc.set_decimation(2, 5);
  for (size_t i = 0; i < f.size(); ++i) b.send_byte(f[i], i == 3 ? 0 : 1);
  for (int i = 0; i < 12 * kCpb; ++i) b.step(1);
  ++framing;
  EXPECT_EQ(b.m->crc_errors, crc);
  EXPECT_EQ(b.m->frame_errors, framing);
  EXPECT_EQ(b.m->accepted, 1);
  EXPECT_EQ(b.m->rejected, 0);
  EXPECT_TRUE(Regs(b) == before);
  // Back-to-back delimiters between frames are idle, not errors; the data
  // path goes on: the next valid command is applied.
  b.send({0, 0, 0});
  b.send(enc.set_decimation(1, 77));
  EXPECT_EQ(b.decim(1), 77);
  EXPECT_EQ(b.m->accepted, 2);
  EXPECT_EQ(b.m->frame_errors, framing);
}
