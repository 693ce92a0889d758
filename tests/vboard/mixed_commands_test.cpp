// rtl/mixed_top.v's command routing, on the virtual board: the mixed build
// for scenes/mixed_neuroskin_split.yaml (dtmf_top beside seed 001's Hall
// top), its pty driven through host/stream (stream::run_board) like eskin
// simulate does. One run, these commands on the one line, in order:
//   HALL_SET_DECOUPLE (well formed)        -> the Hall top accepts it
//   HALL_SET_BASELINE sensor 3 of 1        -> the Hall top rejects it (index)
//   SET_THRESHOLD 1 (well formed)          -> the DTMF top accepts it
//   type 0xA0 (no top's)                   -> the DTMF top rejects it (unknown)
//   REQUEST_STATUS                         -> the DTMF top answers
// Each command must be judged by exactly one top: had the DTMF top kept the
// two Hall commands it would count three rejections (unknown type), and had
// the Hall top kept 0xA0 its last rejection would be 0xA0, not 0x99. Both
// tops' counters come from their own status packets (STATUS, the last
// HALL_DECODE_STATUS); the packets of both share one seq sequence.
#include <gtest/gtest.h>

#include <string>

#include "host/stream/board_link.h"
#include "host/link/hall_packets.h"
#include "host/link/link_encoder.h"
#include "sim/scene.h"
#include "sim/vboard/mixed_build.h"
#include "sim/vboard/vboard_build.h"
#include "sim/vboard/vboard_process.h"

namespace {

using eskin::link::Packet;

TEST(MixedCommands, EachCommandIsJudgedByExactlyOneTop) {
  const std::string scene_file = ESKIN_SOURCE_DIR "/scenes/mixed_neuroskin_split.yaml";
  const auto scene = eskin::sim::load_scene(scene_file);
  const auto dtmf = eskin::vboard::fpga_build_for(scene);
  const auto build = eskin::vboard::mixed_build_for(scene, dtmf);
  const std::string exe = eskin::vboard::board_executable(
      build, [](const std::string& m) { std::printf("%s\n", m.c_str()); });

  eskin::link::LinkEncoder enc;  // one seq counter over all commands
  std::vector<std::vector<uint8_t>> cmds;
  cmds.push_back(eskin::link::hall_set_decouple(enc, 16384, -640, 16384, 320));
  const uint8_t hall_bad_seq = enc.next_seq();
  cmds.push_back(eskin::link::hall_set_baseline(enc, 3, 0, 10));
  cmds.push_back(enc.set_threshold(1, 100));
  const uint8_t unknown_seq = enc.next_seq();
  cmds.push_back(enc.frame(0xA0, 0, {1, 2, 3}));
  cmds.push_back(enc.request_status());

  eskin::vboard::VboardProcess board(exe, eskin::stream::board_args(scene_file, "", cmds));
  const eskin::stream::BoardRun run = eskin::stream::run_board(
      board, int(dtmf.baud()), cmds, 1, [](const Packet&) { return -1L; });
  EXPECT_EQ(board.wait(), 0);
  EXPECT_EQ(run.link.crc_errors + run.link.framing_errors + run.link.payload_errors, 0u);
  EXPECT_EQ(run.link.lost_packets, 0u);  // one seq sequence over both tops

  const Packet* status = nullptr;
  const Packet* hall_status = nullptr;
  for (const Packet& p : run.rx) {
    if (p.type == eskin::link::kStatus) status = &p;
    if (p.type == eskin::link::kHallDecodeStatus) hall_status = &p;
  }
  ASSERT_NE(status, nullptr) << "no STATUS: REQUEST_STATUS did not reach the DTMF top";
  ASSERT_NE(hall_status, nullptr);
  const auto& s = status->status;
  EXPECT_EQ(s.cmd_rejected, 1);
  EXPECT_EQ(s.last_reject_type, 0xA0);
  EXPECT_EQ(s.last_reject_reason, eskin::link::kRejectUnknownType);
  EXPECT_EQ(s.last_reject_seq, unknown_seq);
  EXPECT_GE(s.cmd_accepted, 1);  // SET_THRESHOLD (and REQUEST_STATUS, if counted before the reply)
  EXPECT_LE(s.cmd_accepted, 2);
  EXPECT_EQ(s.cmd_crc_errors + s.cmd_frame_errors + s.cmd_overflows, 0);
  const auto& h = hall_status->hall.status;
  EXPECT_EQ(h.cmd_accepted, 1);
  EXPECT_EQ(h.cmd_rejected, 1);
  EXPECT_EQ(h.last_reject_type, eskin::link::kCmdHallSetBaseline);
  EXPECT_EQ(h.last_reject_reason, eskin::link::kRejectBadIndex);
  EXPECT_EQ(h.last_reject_seq, hall_bad_seq);
  EXPECT_EQ(h.cmd_crc_errors + h.cmd_frame_errors + h.cmd_overflows, 0);
}

}  // namespace
