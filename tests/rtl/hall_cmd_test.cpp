// rtl/hall_cmd.v behind uart_rx and cmd_decoder (tests/rtl/hall_cmd_tb.v),
// fed with command frames built by host/link (hall_packets.h) on a bit-level
// 3 Mbaud line. What docs/protocol.md section 9 promises, checked against
// what the test sent (never read back from the RTL):
//  * an accepted command pulses exactly one load port once, with the
//    payload's fields (row/col/value, sensor/axis/value), and counts;
//  * a rejected one pulses none, counts, records type/reason/seq and pulses
//    `reject`; reasons 1 (unknown type, including a block the build lacks),
//    2 (payload length), 3 (index range), checked in that order;
//  * a long payload is consumed whole (the next command is read correctly);
//    a frame with a bad CRC never reaches hall_cmd.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "Vhall_cmd_tb.h"
#include "Vhall_cmd_tb_ft.h"
#include "host/link/hall_packets.h"
#include "host/link/link_encoder.h"
#include "uart_line.h"

using namespace eskin::link;

namespace {

struct Event {  // one load-port pulse
  char port;    // 'c' LOAD_C, 'b' SET_BASELINE, 'r' RECAPTURE, 'x' reject
  int a = 0, b = 0;
  int32_t value = 0;
};

template <class V>
struct Bench {
  std::unique_ptr<V> m = std::make_unique<V>();
  UartLine line{4};  // 12 MHz / 3 Mbaud
  std::vector<Event> events;
  Bench() {
    m->rst = 1;
    m->rx = 1;
    tick();
    tick();
    m->rst = 0;
  }
  void tick() {
    m->rx = uint8_t(line.tx_level());
    m->clk = 0;
    m->eval();
    m->clk = 1;
    m->eval();
    if (m->rst) return;
    if (m->c_valid) events.push_back({'c', m->c_row, m->c_col, int32_t(m->c_value)});
    if (m->set_valid) events.push_back({'b', m->set_sensor, m->set_axis, int16_t(m->set_value)});
    if (m->recapture) events.push_back({'r'});
    if (m->reject) events.push_back({'x', m->last_type, m->last_reason, m->last_seq});
  }
  // Sends the frames and runs until the line and the pipeline are idle.
  void send(const std::vector<uint8_t>& bytes) {
    line.send(bytes);
    while (line.sending()) tick();
    for (int i = 0; i < 200; ++i) tick();
  }
};

void expect_event(const Event& e, char port, int a, int b, int32_t value) {
  EXPECT_EQ(e.port, port);
  EXPECT_EQ(e.a, a);
  EXPECT_EQ(e.b, b);
  EXPECT_EQ(e.value, value);
}

TEST(HallCmd, AcceptedCommandsPulseTheirPortWithThePayload) {
  Bench<Vhall_cmd_tb_ft> t;  // 3 sensors, F/T
  LinkEncoder e;
  t.send(hall_load_c(e, 5, 8, -123456789));
  t.send(hall_load_c(e, 0, 0, 0x7FFFFFFF));
  t.send(hall_set_baseline(e, 2, 1, -32768));
  t.send(hall_set_baseline(e, 0, 2, 1234));
  t.send(hall_recapture(e));
  ASSERT_EQ(t.events.size(), 5u);
  expect_event(t.events[0], 'c', 5, 8, -123456789);
  expect_event(t.events[1], 'c', 0, 0, 0x7FFFFFFF);
  expect_event(t.events[2], 'b', 2, 1, -32768);
  expect_event(t.events[3], 'b', 0, 2, 1234);
  expect_event(t.events[4], 'r', 0, 0, 0);
  EXPECT_EQ(t.m->accepted, 5);
  EXPECT_EQ(t.m->rejected, 0);
}

TEST(HallCmd, RejectsWithTheFirstFailingReasonAndChangesNothing) {
  Bench<Vhall_cmd_tb_ft> t;
  LinkEncoder e;
  struct Case {
    std::vector<uint8_t> frame;
    uint8_t type, reason;
  };
  std::vector<Case> cases;
  auto add = [&](std::vector<uint8_t> f, uint8_t type, uint8_t reason) {
    cases.push_back({std::move(f), type, reason});
  };
  add(hall_load_c(e, 6, 0, 1), kCmdHallLoadC, 3);          // row 6 of 6
  add(hall_load_c(e, 0, 9, 1), kCmdHallLoadC, 3);          // col 9 of 9
  add(hall_set_baseline(e, 3, 0, 1), kCmdHallSetBaseline, 3);  // sensor 3 of 3
  add(hall_set_baseline(e, 0, 3, 1), kCmdHallSetBaseline, 3);  // axis 3
  add(e.frame(kCmdHallLoadC, 0, {0, 0, 1, 2, 3}), kCmdHallLoadC, 2);  // 5 bytes, not 6
  add(e.frame(kCmdHallRecapture, 0, {0}), kCmdHallRecapture, 2);
  add(e.frame(kCmdHallLoadC, 0, {9, 9, 1}), kCmdHallLoadC, 2);  // length before range
  add(hall_load_curve(e, 0, 0, 0, 1), kCmdHallLoadCurve, 1);  // no force_curve in this top
  add(hall_set_decouple(e, 1, 2, 3, 4), kCmdHallSetDecouple, 1);
  add(e.frame(0x83, 0, {0, 0, 0, 0, 0}), 0x83, 1);             // a DTMF command
  for (const auto& c : cases) t.send(c.frame);
  ASSERT_EQ(t.events.size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(t.events[i].port, 'x');
    EXPECT_EQ(t.events[i].a, cases[i].type);
    EXPECT_EQ(t.events[i].b, cases[i].reason);
    EXPECT_EQ(t.events[i].value, int32_t(i));  // seq: the encoder numbers frames from 0
  }
  EXPECT_EQ(t.m->rejected, cases.size());
  EXPECT_EQ(t.m->accepted, 0);
}

TEST(HallCmd, LoadCIsUnknownWithoutFtAndSensorRangeFollowsNs) {
  Bench<Vhall_cmd_tb> t;  // 16 sensors, no F/T
  LinkEncoder e;
  t.send(hall_load_c(e, 0, 0, 1));
  t.send(hall_set_baseline(e, 15, 2, -7));
  t.send(hall_set_baseline(e, 16, 0, 1));
  ASSERT_EQ(t.events.size(), 3u);
  expect_event(t.events[0], 'x', kCmdHallLoadC, 1, 0);
  expect_event(t.events[1], 'b', 15, 2, -7);
  expect_event(t.events[2], 'x', kCmdHallSetBaseline, 3, 2);
}

TEST(HallCmd, LongPayloadIsConsumedAndBadCrcNeverArrives) {
  Bench<Vhall_cmd_tb_ft> t;
  LinkEncoder e;
  std::vector<uint8_t> bytes = e.frame(kCmdHallLoadC, 0, std::vector<uint8_t>(40, 0x5A));
  // A LOAD_C frame with one payload bit flipped after its CRC was computed.
  std::vector<uint8_t> raw = raw_frame(kCmdHallLoadC, e.next_seq(), 0, {1, 1, 1, 0, 0, 0});
  raw[10] ^= 0x04;
  std::vector<uint8_t> bad = cobs_encode(raw);
  bad.push_back(0);
  e.set_next_seq(uint8_t(e.next_seq() + 1));
  auto good = hall_set_baseline(e, 1, 1, 99);
  bytes.insert(bytes.end(), bad.begin(), bad.end());
  bytes.insert(bytes.end(), good.begin(), good.end());
  t.send(bytes);
  ASSERT_EQ(t.events.size(), 2u);
  expect_event(t.events[0], 'x', kCmdHallLoadC, 2, 0);
  expect_event(t.events[1], 'b', 1, 1, 99);
  EXPECT_EQ(t.m->crc_errors, 1);
}

}  // namespace
