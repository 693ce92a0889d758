// Hall packets on the host link: every type round-trips through the
// encoder and the streaming decoder (two implementations of COBS and CRC),
// payloads of the wrong size are counted and skipped, the stream goes on.
#include <gtest/gtest.h>

#include "host/link/hall_packets.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"

namespace eskin::link {
namespace {

std::vector<Packet> decode(const std::vector<uint8_t>& bytes, LinkDecoder& d) {
  d.feed(bytes);
  std::vector<Packet> out;
  Packet p;
  while (d.pop(p)) out.push_back(p);
  return out;
}

TEST(HallLink, DataPacketsRoundTrip) {
  LinkEncoder e;
  std::vector<uint8_t> w;
  auto add = [&](const std::vector<uint8_t>& f) { w.insert(w.end(), f.begin(), f.end()); };
  const std::vector<HallDeltaRecord> s = {{3, 0x01, 54321, -32768, 32767, 0}, {15, 0x80, 7, 1, -2, 3}};
  add(hall_deltas(e, 11, s));
  add(hall_decouple3(e, 12, {-2099, 7975, 117286817, 1, 0x04}));
  WrenchRecord wr;
  for (int i = 0; i < 6; ++i) wr.w[i] = (i % 2 ? -1 : 1) * (1000 * i + 7);
  wr.w[5] = int32_t(0x80000000);
  wr.flags = 0x20;
  add(hall_wrench6(e, 13, wr));
  add(hall_force_curve(e, 14, {{0, 0, 0, 99, 60}, {8, 2, 0x01, 100, 15500}}));
  add(hall_decode_status(e, 15, {1, 2, 3, 4, 5, 6, 7, 0x9B, 1, 200}));
  LinkDecoder d;
  // Fed in 5-byte pieces: any split of the stream decodes the same.
  std::vector<Packet> got;
  for (size_t i = 0; i < w.size(); i += 5) {
    const std::vector<uint8_t> piece(w.begin() + long(i), w.begin() + long(std::min(w.size(), i + 5)));
    auto more = decode(piece, d);
    got.insert(got.end(), more.begin(), more.end());
  }
  ASSERT_EQ(got.size(), 5u);
  EXPECT_EQ(d.stats().frames_ok, 5u);
  ASSERT_EQ(got[0].hall.deltas.size(), 2u);
  EXPECT_EQ(got[0].type, kHallDeltas);
  EXPECT_EQ(got[0].hall.deltas[0].t16, 54321);
  EXPECT_EQ(got[0].hall.deltas[0].dx, -32768);
  EXPECT_EQ(got[0].hall.deltas[0].dy, 32767);
  EXPECT_EQ(got[0].hall.deltas[1].dy, -2);
  EXPECT_EQ(got[1].hall.decouple.sz, 117286817);
  EXPECT_EQ(got[1].hall.decouple.rx, -2099);
  EXPECT_EQ(got[1].hall.decouple.valid, 1);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(got[2].hall.wrench.w[i], wr.w[i]);
  EXPECT_EQ(got[2].hall.wrench.flags, 0x20);
  ASSERT_EQ(got[3].hall.forces.size(), 2u);
  EXPECT_EQ(got[3].hall.forces[1].force_mn, 15500);
  EXPECT_EQ(got[3].hall.forces[1].range, 2);
  EXPECT_EQ(got[4].hall.status.ft_skipped, 2);
  EXPECT_EQ(got[4].hall.status.cmd_rejected, 4);
  EXPECT_EQ(got[4].hall.status.cmd_overflows, 7);
  EXPECT_EQ(got[4].hall.status.last_reject_type, 0x9B);
  EXPECT_EQ(got[4].hall.status.last_reject_seq, 200);
  EXPECT_EQ(got[4].t, 15u);
}

TEST(HallLink, CommandsRoundTrip) {
  LinkEncoder e;
  LinkDecoder d;
  auto one = [&](const std::vector<uint8_t>& f) {
    auto v = decode(f, d);
    EXPECT_EQ(v.size(), 1u);
    return v.empty() ? Packet{} : v[0];
  };
  Packet p = one(hall_load_c(e, 5, 8, -123456789));
  EXPECT_EQ(p.type, kCmdHallLoadC);
  EXPECT_EQ(p.hall.cmd.index, 5);
  EXPECT_EQ(p.hall.cmd.sub, 8);
  EXPECT_EQ(p.hall.cmd.value, -123456789);
  p = one(hall_set_baseline(e, 2, 1, -1234));
  EXPECT_EQ(p.hall.cmd.value, -1234);
  p = one(hall_recapture(e));
  EXPECT_EQ(p.type, kCmdHallRecapture);
  p = one(hall_load_curve(e, 8, 12, 2, 3906));
  EXPECT_EQ(p.hall.cmd.which, 2);
  EXPECT_EQ(p.hall.cmd.value, 3906);
  p = one(hall_set_decouple(e, -16384, -25748, -16384, -46523));
  EXPECT_EQ(p.hall.cmd.k1, -16384);
  EXPECT_EQ(p.hall.cmd.c2, -46523);
}

TEST(HallLink, WrongPayloadSizesAreCountedAndSkipped) {
  LinkEncoder e;
  LinkDecoder d;
  std::vector<uint8_t> w;
  auto add = [&](const std::vector<uint8_t>& f) { w.insert(w.end(), f.begin(), f.end()); };
  add(e.frame(kHallWrench6, 1, std::vector<uint8_t>(24, 1)));     // one byte short
  add(e.frame(kHallDeltas, 2, std::vector<uint8_t>(13, 1)));      // not a multiple of 10
  add(e.frame(kHallDecouple3, 3, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0}));  // valid = 2
  add(e.frame(kCmdHallSetBaseline, 0, {1, 2, 3}));
  add(hall_decode_status(e, 4, {}));                               // a good one after them
  const auto got = decode(w, d);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].type, kHallDecodeStatus);
  EXPECT_EQ(d.stats().payload_errors, 4u);
}

}  // namespace
}  // namespace eskin::link
