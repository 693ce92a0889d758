// eskin config's hall-* commands against the FPGA itself: the Hall top
// built for seed 001 (hall_baseline, hall_decouple, command path) on the
// virtual board, its pty opened by the real eskin binary as a serial port.
// The verdicts are the RTL's (rtl/hall_cmd.v, docs/protocol.md section 9),
// read from the HALL_DECODE_STATUS packets it sends every 64 frames and
// after a rejection: a well-formed HALL_SET_DECOUPLE is accepted; a
// HALL_SET_BASELINE for sensor 3 of a one-sensor build is rejected with
// reason 3 (index out of range).
#include <gtest/gtest.h>

#include <string>

#include "run_command.h"
#include "sim/scene.h"
#include "sim/vboard/hall_build.h"
#include "sim/vboard/vboard_build.h"
#include "sim/vboard/vboard_process.h"

namespace {

using vboard_test::run;

std::string hall_board() {
  const auto scene = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/hall_001_split.yaml");
  return eskin::vboard::board_executable(eskin::vboard::hall_build_for(scene),
                                         [](const std::string& m) { std::printf("%s\n", m.c_str()); });
}

// One command on a fresh board run; the board stops when eskin config
// closes the port.
int config(const std::string& exe, const std::string& command, std::string* out) {
  eskin::vboard::VboardProcess board(exe, {ESKIN_SOURCE_DIR "/scenes/hall_001_split.yaml"});
  const int st = run(std::string(ESKIN_BIN) + " config --port " + board.pty() +
                         " --timeout-ms 30000 " + command, out);
  board.wait();
  return st;
}

TEST(ConfigHall, TheHallTopAcceptsAndRejectsAsItsCommandPathSays) {
  const std::string exe = hall_board();
  std::string out;
  EXPECT_EQ(config(exe, "hall-set-decouple 16384 -640 16384 320", &out), 0) << out;
  EXPECT_NE(out.find("accepted"), std::string::npos) << out;
  EXPECT_NE(out.find("hall decode status: accepted 1, rejected 0"), std::string::npos) << out;
  EXPECT_EQ(config(exe, "hall-set-baseline 3 0 10", &out), 3) << out;
  EXPECT_NE(out.find("rejected: index out of range"), std::string::npos) << out;
}

TEST(ConfigHall, BadArgumentsAreRefusedBeforeAnythingIsSent) {
  std::string out;
  EXPECT_NE(run(std::string(ESKIN_BIN) + " config --port /dev/null hall-set-baseline 0 0 40000", &out), 0);
  EXPECT_NE(out.find("value '40000': expected -32768..32767"), std::string::npos) << out;
}

}  // namespace
