// host/link/link_decoder against host/link/link_encoder (two independent
// implementations of CRC-16 and COBS) and against catalogue values.
//
// Bounds checked and why they hold:
//  * CRC-16/CCITT-FALSE of "123456789" is 0x29B1: the published check value
//    of that CRC (Greg Cook's CRC catalogue), for both implementations.
//  * Every single-bit error inside a raw frame is detected: an error
//    polynomial x^i is never a multiple of g(x) = x^16 + x^12 + x^5 + 1:
//    for any q(x) != 0, q(x) g(x) has at least two terms (the lowest term of
//    q times 1 and the highest times x^16), so it is never a monomial.
//  * Every single-bit error on the wire (COBS layer included) yields no
//    packet: either the COBS structure or the length field breaks (counted
//    as a framing error) or the decoded bytes change, which the CRC catches.
//    The latter is a multi-bit change, where CRC-16 misses at most 2^-16 of
//    patterns; the frames here are fixed, so the outcome is deterministic.
//  * A corrupt frame never stops the stream: the next frame after the next
//    0x00 decodes.
//  * Sequence gaps: n frames removed from a run are counted as exactly one
//    gap of n lost packets (mod 256 arithmetic, so 255 -> 0 is no gap).
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

using namespace eskin::link;

namespace {

std::vector<Packet> decode_all(LinkDecoder& d) {
  std::vector<Packet> out;
  Packet p;
  while (d.pop(p)) out.push_back(p);
  return out;
}

std::vector<uint8_t> random_bytes(std::mt19937& rng, size_t n, bool allow_zero = true) {
  std::vector<uint8_t> v(n);
  for (auto& b : v) {
    b = uint8_t(rng());
    if (!allow_zero && b == 0) b = 1;
  }
  return v;
}

}  // namespace

TEST(LinkCrc, CatalogueCheckValue) {
  const std::string s = "123456789";
  const auto* p = reinterpret_cast<const uint8_t*>(s.data());
  EXPECT_EQ(crc16_ccitt_false(p, s.size()), 0x29B1);
  EXPECT_EQ(crc16_table(p, s.size()), 0x29B1);
}

TEST(LinkCrc, TableAndBitwiseAgreeOnRandomData) {
  std::mt19937 rng(1);
  for (int i = 0; i < 200; ++i) {
    const auto v = random_bytes(rng, rng() % 300);
    ASSERT_EQ(crc16_ccitt_false(v.data(), v.size()), crc16_table(v.data(), v.size()));
  }
}

// Hand-encoded COBS vectors (each block: code = 1 + run length of non-zero
// bytes; a final block always closes the frame).
TEST(LinkCobs, HandVectors) {
  using V = std::vector<uint8_t>;
  EXPECT_EQ(cobs_encode(V{}), (V{0x01}));
  EXPECT_EQ(cobs_encode(V{0x00}), (V{0x01, 0x01}));
  EXPECT_EQ(cobs_encode(V{0x00, 0x00}), (V{0x01, 0x01, 0x01}));
  EXPECT_EQ(cobs_encode(V{0x11, 0x22, 0x00, 0x33}), (V{0x03, 0x11, 0x22, 0x02, 0x33}));
  EXPECT_EQ(cobs_encode(V{0x11, 0x00, 0x00, 0x00}), (V{0x02, 0x11, 0x01, 0x01, 0x01}));
  V run(254);
  for (int i = 0; i < 254; ++i) run[size_t(i)] = uint8_t(i + 1);
  V enc = cobs_encode(run);
  ASSERT_EQ(enc.size(), 256u);
  EXPECT_EQ(enc[0], 0xFF);
  EXPECT_EQ(enc[255], 0x01);  // closing empty block
}

TEST(LinkDecoder, RoundTripEveryType) {
  LinkEncoder enc;
  LinkDecoder dec;
  StatusBlock st;
  st.cmd_crc_errors = 3; st.cmd_frame_errors = 4; st.cmd_accepted = 0x1234;
  st.cmd_rejected = 7; st.last_reject_type = kCmdSetDecimation;
  st.last_reject_reason = kRejectBadValue; st.last_reject_seq = 9;
  st.output_mask = 0x0B; st.dropped_frames = 0xFFFF; st.adc_overruns = 5;
  st.uart_rx_errors = 6; st.samples = 0xDEADBEEF;
  dec.feed(enc.amplitudes(100, {0, 1, 0xFFFF, 0x8000, 0x00FF, 0xFF00}));
  dec.feed(enc.taxels_dense(200, 2, 3, {1, 2, 3, 4, 5, 6}));
  dec.feed(enc.taxels_sparse(300, {{0, 1, 7}, {2, 2, 0xFFFF}}));
  dec.feed(enc.spikes(400, {{0, 0, 3}, {31, 1, 0x1FF}}));
  dec.feed(enc.status(500, st));
  dec.feed(enc.set_carrier_inc(5, 0x12345678));
  dec.feed(enc.set_neuron(2, -1234));
  dec.feed(enc.set_output_mask(0x0F));
  dec.feed(enc.request_status());
  auto ps = decode_all(dec);
  ASSERT_EQ(ps.size(), 9u);
  for (size_t i = 0; i < ps.size(); ++i) EXPECT_EQ(ps[i].seq, i);
  EXPECT_EQ(ps[0].type, kAmplitudes);
  EXPECT_EQ(ps[0].t, 100u);
  EXPECT_EQ(ps[0].amplitudes, (std::vector<uint16_t>{0, 1, 0xFFFF, 0x8000, 0x00FF, 0xFF00}));
  EXPECT_EQ(ps[1].rows, 2);
  EXPECT_EQ(ps[1].cols, 3);
  EXPECT_EQ(ps[1].taxels, (std::vector<uint16_t>{1, 2, 3, 4, 5, 6}));
  ASSERT_EQ(ps[2].sparse.size(), 2u);
  EXPECT_EQ(ps[2].sparse[1].row, 2);
  EXPECT_EQ(ps[2].sparse[1].value, 0xFFFF);
  ASSERT_EQ(ps[3].spikes.size(), 2u);
  EXPECT_EQ(ps[3].spikes[1].dt, 31);
  EXPECT_EQ(ps[3].spikes[1].layer, 1);
  EXPECT_EQ(ps[3].spikes[1].neuron, 0x1FF);
  const StatusBlock& s = ps[4].status;
  EXPECT_EQ(s.cmd_crc_errors, 3); EXPECT_EQ(s.cmd_frame_errors, 4);
  EXPECT_EQ(s.cmd_accepted, 0x1234); EXPECT_EQ(s.cmd_rejected, 7);
  EXPECT_EQ(s.last_reject_type, kCmdSetDecimation);
  EXPECT_EQ(s.last_reject_reason, kRejectBadValue); EXPECT_EQ(s.last_reject_seq, 9);
  EXPECT_EQ(s.output_mask, 0x0B); EXPECT_EQ(s.dropped_frames, 0xFFFF);
  EXPECT_EQ(s.adc_overruns, 5); EXPECT_EQ(s.uart_rx_errors, 6);
  EXPECT_EQ(s.samples, 0xDEADBEEFu);
  EXPECT_EQ(ps[5].cmd_index, 5); EXPECT_EQ(ps[5].cmd_value, 0x12345678u);
  EXPECT_EQ(int32_t(ps[6].cmd_value), -1234);
  EXPECT_EQ(ps[7].cmd_value, 0x0Fu);
  EXPECT_EQ(ps[8].payload.size(), 0u);
  EXPECT_EQ(dec.stats().frames_ok, 9u);
  EXPECT_EQ(dec.stats().crc_errors + dec.stats().framing_errors + dec.stats().seq_gaps, 0u);
}

// Random payloads (zeros included, lengths across the 254-byte COBS block
// size) fed in random chunk sizes come back byte for byte.
TEST(LinkDecoder, RandomPayloadsAnySplit) {
  std::mt19937 rng(7);
  LinkEncoder enc;
  LinkDecoder dec;
  std::vector<std::vector<uint8_t>> sent;
  std::vector<uint8_t> stream;
  for (int i = 0; i < 300; ++i) {
    const size_t n = 2 * (rng() % 400);
    auto payload = random_bytes(rng, n);
    if (i % 3 == 0) std::fill(payload.begin(), payload.end(), 0xAB);  // long zero-free runs
    sent.push_back(payload);
    auto f = enc.frame(kAmplitudes, uint32_t(i) * 1000, payload);
    stream.insert(stream.end(), f.begin(), f.end());
  }
  for (size_t i = 0; i < stream.size();) {
    const size_t k = std::min(stream.size() - i, size_t(1 + rng() % 64));
    dec.feed(stream.data() + i, k);
    i += k;
  }
  auto ps = decode_all(dec);
  ASSERT_EQ(ps.size(), sent.size());
  for (size_t i = 0; i < ps.size(); ++i) {
    EXPECT_EQ(ps[i].payload, sent[i]) << "packet " << i;
    EXPECT_EQ(ps[i].t, uint32_t(i) * 1000);
    EXPECT_EQ(ps[i].seq, uint8_t(i));
  }
  EXPECT_EQ(dec.stats().seq_gaps, 0u);  // 300 packets: wraps 255 -> 0 once
}

TEST(LinkDecoder, EverySingleBitErrorInRawFrameIsDetected) {
  std::mt19937 rng(3);
  for (int f = 0; f < 4; ++f) {
    const auto payload = random_bytes(rng, size_t(4 + 20 * f));
    const auto raw = raw_frame(kAmplitudes, uint8_t(f), 12345u * f, payload);
    for (size_t bit = 0; bit < raw.size() * 8; ++bit) {
      auto bad = raw;
      bad[bit / 8] ^= uint8_t(1u << (bit % 8));
      auto wire = cobs_encode(bad);
      wire.push_back(0);
      LinkDecoder dec;
      dec.feed(wire);
      ASSERT_EQ(dec.pending(), 0u) << "frame " << f << " bit " << bit;
      const auto& s = dec.stats();
      // A flip in the length field shows as a length mismatch, elsewhere as a CRC error.
      const bool in_len = bit / 8 == 6 || bit / 8 == 7;
      ASSERT_EQ(in_len ? s.framing_errors : s.crc_errors, 1u) << "bit " << bit;
    }
  }
}

TEST(LinkDecoder, EverySingleBitErrorOnTheWireYieldsNoPacketAndStreamGoesOn) {
  std::mt19937 rng(4);
  LinkEncoder enc;
  for (int f = 0; f < 3; ++f) {
    const auto frame = enc.amplitudes(777, {1, 2, 0, uint16_t(rng()), 0x00FF, 0});
    const auto next = enc.amplitudes(778, {42});
    for (size_t bit = 0; bit < (frame.size() - 1) * 8; ++bit) {  // not the delimiter
      auto bad = frame;
      bad[bit / 8] ^= uint8_t(1u << (bit % 8));
      LinkDecoder dec;
      dec.feed(bad);
      ASSERT_EQ(dec.pending(), 0u) << "bit " << bit;
      ASSERT_GE(dec.stats().crc_errors + dec.stats().framing_errors, 1u);
      dec.feed(next);
      Packet p;
      ASSERT_TRUE(dec.pop(p));
      ASSERT_EQ(p.amplitudes, std::vector<uint16_t>{42});
    }
  }
}

TEST(LinkDecoder, TruncatedFramesAreCountedAndSkipped) {
  LinkEncoder enc;
  const auto frame = enc.spikes(5, {{1, 0, 2}, {3, 1, 4}});
  const auto good = enc.spikes(6, {{9, 0, 9}});
  for (size_t cut = 1; cut + 1 < frame.size(); ++cut) {
    LinkDecoder dec;
    std::vector<uint8_t> s(frame.begin(), frame.begin() + long(cut));
    s.push_back(0);
    dec.feed(s);
    dec.feed(good);
    EXPECT_EQ(dec.stats().crc_errors + dec.stats().framing_errors, 1u) << "cut " << cut;
    auto ps = decode_all(dec);
    ASSERT_EQ(ps.size(), 1u);
    EXPECT_EQ(ps[0].t, 6u);
  }
}

TEST(LinkDecoder, GarbageBetweenFrames) {
  std::mt19937 rng(5);
  LinkEncoder enc;
  LinkDecoder dec;
  int expected = 0;
  for (int i = 0; i < 50; ++i) {
    dec.feed(enc.amplitudes(uint32_t(i), {uint16_t(i)}));
    ++expected;
    // Garbage that ends with a delimiter: the next frame is untouched.
    auto g = random_bytes(rng, 1 + rng() % 40);
    g.push_back(0);
    dec.feed(g);
  }
  auto ps = decode_all(dec);
  ASSERT_EQ(ps.size(), size_t(expected));
  for (int i = 0; i < expected; ++i) EXPECT_EQ(ps[size_t(i)].amplitudes[0], i);
  EXPECT_GE(dec.stats().crc_errors + dec.stats().framing_errors, 1u);
  EXPECT_EQ(dec.stats().seq_gaps, 0u);

  // Garbage with no delimiter merges with the following frame: that one frame
  // is lost (counted), the one after it decodes, and the loss shows as a gap.
  LinkDecoder d2;
  d2.feed(enc.amplitudes(1, {1}));
  d2.feed(std::vector<uint8_t>{0x55, 0x66, 0x77});
  d2.feed(enc.amplitudes(2, {2}));
  d2.feed(enc.amplitudes(3, {3}));
  auto p2 = decode_all(d2);
  ASSERT_EQ(p2.size(), 2u);
  EXPECT_EQ(p2[1].t, 3u);
  EXPECT_EQ(d2.stats().crc_errors + d2.stats().framing_errors, 1u);
  EXPECT_EQ(d2.stats().seq_gaps, 1u);
  EXPECT_EQ(d2.stats().lost_packets, 1u);
}

TEST(LinkDecoder, SequenceGapsCounted) {
  LinkEncoder enc;
  LinkDecoder dec;
  // 600 frames (wrapping the 8-bit sequence twice); drop 3 at i=10, 1 at 300, 5 at 590.
  for (int i = 0; i < 600; ++i) {
    auto f = enc.amplitudes(uint32_t(i), {});
    const bool drop = (i >= 10 && i < 13) || i == 300 || (i >= 590 && i < 595);
    if (!drop) dec.feed(f);
  }
  EXPECT_EQ(dec.stats().seq_gaps, 3u);
  EXPECT_EQ(dec.stats().lost_packets, 9u);
  EXPECT_EQ(dec.stats().frames_ok, 591u);
}

// A board reset mid-stream (as on the virtual board with --fault reset):
// its seq and t start again from 0. Without restart detection the jump from
// seq 100 to 2 would count as 157 lost packets; the packets the restarted
// board numbered 0 and 1 are the only ones lost, and t falling behind the
// last packet of its type, with the numbering broken, is how the host
// tells. A t that wraps at 2^32 (behind by more than half the range) is no
// restart, nor a t behind with the numbering going on.
TEST(LinkDecoder, ABoardRestartIsCountedAndItsLossesAreThePacketsSinceIt) {
  LinkDecoder dec;
  {
    LinkEncoder before;
    for (int i = 0; i <= 100; ++i) dec.feed(before.amplitudes(uint32_t(1000 + 35 * i), {}));
  }
  LinkEncoder after;  // the restarted board: seq 0 again
  for (int i = 0; i < 10; ++i) {
    const auto f = after.amplitudes(uint32_t(31 + 35 * i), {});
    if (i >= 2) dec.feed(f);
  }
  EXPECT_EQ(dec.stats().restarts, 1u);
  EXPECT_EQ(dec.stats().seq_gaps, 1u);
  EXPECT_EQ(dec.stats().lost_packets, 2u);
  EXPECT_EQ(dec.stats().frames_ok, 109u);

  LinkDecoder wrap;
  LinkEncoder enc;
  wrap.feed(enc.amplitudes(0xFFFFFFF0u, {}));
  wrap.feed(enc.amplitudes(0x00000013u, {}));  // t wrapped: 35 samples on
  EXPECT_EQ(wrap.stats().restarts, 0u);
  EXPECT_EQ(wrap.stats().lost_packets, 0u);

  // t behind with the numbering going on: no restart (the sender chose t).
  LinkDecoder same;
  LinkEncoder one;
  same.feed(one.amplitudes(5000, {}));
  same.feed(one.amplitudes(10, {}));
  EXPECT_EQ(same.stats().restarts, 0u);
  EXPECT_EQ(same.stats().seq_gaps, 0u);
}

TEST(LinkDecoder, OversizedAndMalformedPayloads) {
  LinkEncoder enc;
  LinkDecoder dec(16);  // payloads above 16 bytes cannot be buffered
  dec.feed(enc.frame(kAmplitudes, 0, std::vector<uint8_t>(100, 1)));
  EXPECT_EQ(dec.stats().framing_errors, 1u);
  dec.feed(enc.frame(kAmplitudes, 0, {1, 2, 3}));  // odd length: not u16s
  dec.feed(enc.frame(0x7E, 0, {}));                // unknown type
  EXPECT_EQ(dec.stats().payload_errors, 2u);
  dec.feed(enc.amplitudes(9, {9}));
  auto ps = decode_all(dec);
  ASSERT_EQ(ps.size(), 1u);
  EXPECT_EQ(ps[0].t, 9u);
}

TEST(LinkDecoder, CallbackReceivesPackets) {
  LinkEncoder enc;
  LinkDecoder dec;
  int n = 0;
  dec.on_packet([&](const Packet& p) { n += p.amplitudes.at(0); });
  dec.feed(enc.amplitudes(0, {3}));
  dec.feed(enc.amplitudes(0, {4}));
  EXPECT_EQ(n, 7);
  EXPECT_EQ(dec.pending(), 0u);
}

// HALL_SAMPLES (0x10) and HALL_BUS_STATUS (0x20), byte layouts of
// docs/protocol.md section 8 written out by hand.
TEST(LinkDecoder, HallPackets) {
  LinkEncoder enc;
  LinkDecoder dec;
  // Two readings: id 3 with X saturated, id 4 missing (no data).
  const std::vector<uint8_t> samples = {3, 0x01, 0x34, 0x12, 0xFF, 0x7F, 0x02, 0x01, 0x00, 0x80,
                                        4, 0x08, 0,    0,    0,    0,    0,    0,    0,    0};
  const std::vector<uint8_t> buses = {1, 0, 2, 0, 3, 0, 4, 0, 0xFF, 0xFF};
  dec.feed(enc.frame(kHallSamples, 777, samples));
  dec.feed(enc.frame(kHallBusStatus, 778, buses));
  dec.feed(enc.frame(kHallSamples, 779, {1, 2, 3}));  // not a multiple of 10
  Packet p;
  ASSERT_TRUE(dec.pop(p));
  ASSERT_EQ(p.hall_samples.size(), 2u);
  const HallSample& a = p.hall_samples[0];
  EXPECT_EQ(a.id, 3);
  EXPECT_EQ(a.t16, 0x1234);
  EXPECT_EQ(a.x, 0x7FFF);
  EXPECT_EQ(a.y, 0x0102);
  EXPECT_EQ(a.z, 0x8000);
  EXPECT_TRUE(a.has_data());
  EXPECT_EQ(a.flags & HallSample::kSatX, HallSample::kSatX);
  EXPECT_FALSE(p.hall_samples[1].has_data());
  ASSERT_TRUE(dec.pop(p));
  ASSERT_EQ(p.hall_buses.size(), 1u);
  EXPECT_EQ(p.hall_buses[0].nacks, 1);
  EXPECT_EQ(p.hall_buses[0].status_errors, 2);
  EXPECT_EQ(p.hall_buses[0].reply_errors, 3);
  EXPECT_EQ(p.hall_buses[0].recoveries, 4);
  EXPECT_EQ(p.hall_buses[0].bus_errors, 0xFFFF);
  EXPECT_FALSE(dec.pop(p));
  EXPECT_EQ(dec.stats().payload_errors, 1u);
}
