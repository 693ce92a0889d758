// `eskin hall-top SCENE`: the hall_top parameters a Hall scene needs, run as
// a user runs it. The expected values are worked out here from the scene
// file and the MLX90393 datasheet, not read from the generator:
//  * seed 002: one bus of three sensors at 0x0C, 0x0D, 0x0E (7 bits per
//    slot, slot 0 low: 0x0C | 0x0D << 7 | 0x0E << 14 = 0x3868C), no mux;
//    REG0 HALLCONF 0xC, GAIN_SEL 0; REG1 TRIG_INT (DRDY on INT), I2C only,
//    burst of Z, Y, X; REG2 OSR 0, DIG_FILT 2 (2 << 2). XYZ conversion
//    220 + 360 + 3 (67 + 64 (2 + 4)) + 120 = 2053 us: the single-mode wait
//    is 1.2 of it in clocks (rounded up), the burst stale limit 1.5 of it;
//    `decode: [baseline, wrench]` gives DELTAS and FT on slots 0..2.
//  * the clock scales only CLK_HZ and the two waits;
//  * a DTMF scene and a scene whose buses differ in size are refused with
//    the field named, non-zero exit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"

namespace {

std::string seed002(const std::string& clk, const std::string& conv, const std::string& stale) {
  return "CLK_HZ=" + clk +
         "\nNB=1\nNSB=3\nADDR=21'h03868c\nMUX_ADDR=21'h000000\nMUX_CH=9'h000\nREG0=16'h000c\n"
         "REG1=16'he380\nREG2=16'h0008\nCONV_CYC=" + conv + "\nSTALE_CYC=" + stale +
         "\nDELTAS=1\nFT=1\nFT_ID=0\n";
}

TEST(HallTopCli, Seed002ParametersFromTheSceneAndTheDatasheet) {
  const std::string scene = ESKIN_SOURCE_DIR "/scenes/hall_002_magtac.yaml";
  const CliResult r = run_eskin("hall-top " + scene);
  ASSERT_EQ(r.status, 0) << r.out;
  // 2053 us * 1.2 * 12 = 29563.2 -> 29564; * 1.5 * 12 = 36954.
  EXPECT_EQ(r.out, seed002("12000000", "29564", "36954"));
  // At 24 MHz: 59126.4 -> 59127 and 73908.
  const CliResult r24 = run_eskin("hall-top " + scene + " --clk-mhz 24");
  ASSERT_EQ(r24.status, 0) << r24.out;
  EXPECT_EQ(r24.out, seed002("24000000", "59127", "73908"));
}

TEST(HallTopCli, ScenesItCannotBuildAreRefusedNamingTheField) {
  const CliResult dtmf = run_eskin("hall-top " ESKIN_SOURCE_DIR "/scenes/planned3x3.yaml");
  EXPECT_NE(dtmf.status, 0);
  EXPECT_NE(dtmf.out.find("hall"), std::string::npos) << dtmf.out;
  // Seed 002 with its third sensor moved to a second bus: 2 + 1 sensors.
  std::ifstream in(ESKIN_SOURCE_DIR "/scenes/hall_002_magtac.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string y = text.str();
  const std::string from = "bus: 0, i2c_address: 0x0E";
  ASSERT_NE(y.find(from), std::string::npos);
  y.replace(y.find(from), from.size(), "bus: 1, i2c_address: 0x0E");
  const auto path = std::filesystem::temp_directory_path() / "eskin_hall_top_uneven.yaml";
  std::ofstream(path) << y;
  const CliResult uneven = run_eskin("hall-top " + path.string());
  std::filesystem::remove(path);
  EXPECT_NE(uneven.status, 0);
  EXPECT_NE(uneven.out.find("hall.sensors"), std::string::npos) << uneven.out;
  EXPECT_NE(uneven.out.find("bus 1 has 1 sensors"), std::string::npos) << uneven.out;
}

}  // namespace
