// `eskin simulate` on a scene with both a DTMF skin and Hall sensors
// (scenes/mixed_neuroskin_split.yaml: neuroskin2's 3x3 skin beside seed
// 001's split cell), as a user runs it: the scene's build of
// rtl/mixed_top.v on the virtual board, the AD7476A and the MLX90393 on its
// pins, both tops' packets on one link. Checked:
//  * one link, nothing lost: no CRC or framing error and no seq gap over
//    both tops' packets (one link_framer numbers them all), packets of both;
//  * sharing the link changes none of the skin's packets: they equal, type,
//    time and values, those of the same skin simulated alone (the skin's
//    samples and commands are the same, the DTMF top is the same RTL; only
//    their arrival times differ);
//  * commands reach the right top: the Hall top accepted all 4 of its
//    commands and rejected none (the DTMF top's decoder drops them; had it
//    kept them, the Hall side would miss them and its forces would be off),
//    and the skin's output mask took effect (amplitudes, taxels, spikes
//    arrive);
//  * the Hall force within 2.5 % of full scale, the bound of the Hall-only
//    test (tests/vboard/simulate_hall_test.cpp), for the same reason;
//  * one Hall frame per 2053 us conversion over the run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.h"

namespace {

namespace fs = std::filesystem;
using vboard_test::run;
using vboard_test::slurp;

// The NDJSON rows without their arrival times.
std::vector<std::string> rows_without_arrival(const fs::path& p) {
  std::vector<std::string> rows;
  std::istringstream in(slurp(p));
  for (std::string line; std::getline(in, line);) {
    nlohmann::json j = nlohmann::json::parse(line);
    j.erase("arrival_us");
    rows.push_back(j.dump());
  }
  return rows;
}

TEST(SimulateMixed, SkinAndHallSensorsShareOneLinkAndEachTopIsUnchanged) {
  const fs::path tmp = fs::path(testing::TempDir());
  const fs::path out = tmp / "sim_mixed", alone = tmp / "sim_mixed_skin_alone";
  fs::remove_all(out);
  fs::remove_all(alone);
  std::string log;
  ASSERT_EQ(run(std::string(ESKIN_BIN) + " simulate " ESKIN_SOURCE_DIR
                "/scenes/mixed_neuroskin_split.yaml --out " + out.string(), &log), 0) << log;
  const nlohmann::json sum = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(sum.at("top"), "mixed_top");
  EXPECT_EQ(sum.at("link_errors").get<int>(), 0);
  EXPECT_EQ(sum.at("lost_packets").get<int>(), 0);
  EXPECT_GT(sum.at("dtmf_packets").get<int>(), 0);
  EXPECT_GT(sum.at("hall_packets").get<int>(), 0);
  EXPECT_TRUE(fs::exists(out / "report.html"));
  EXPECT_TRUE(fs::exists(out / "skin" / "report.html"));
  EXPECT_TRUE(fs::exists(out / "hall" / "report.html"));

  const nlohmann::json& hall = sum.at("hall");
  EXPECT_EQ(hall.at("i2c_violations").get<int>(), 0);
  EXPECT_EQ(hall.at("commands_sent").get<int>(), 4);
  EXPECT_EQ(hall.at("commands_accepted").get<int>(), 4);
  EXPECT_EQ(hall.at("commands_rejected").get<int>(), 0);
  EXPECT_LT(hall.at("decouple").at("fpga_shear").get<double>(), 0.025);
  EXPECT_LT(hall.at("decouple").at("fpga_normal").get<double>(), 0.025);
  EXPECT_GE(hall.at("decouple").at("fpga_frames").get<int>(), 100);  // four holds, 300 ms
  // 0.602 s (scene and tail) at one frame per 2053 us: 293; the first
  // round goes to configuring the sensor.
  EXPECT_GE(hall.at("frames").get<int>(), 290);
  EXPECT_LE(hall.at("frames").get<int>(), 294);

  const nlohmann::json& skin = sum.at("skin");
  EXPECT_EQ(skin.at("frame_overruns").get<int>(), 0);
  EXPECT_EQ(skin.at("dropped_packets").get<int>(), 0);
  EXPECT_GT(skin.at("fpga_spikes").get<int>(), 0);

  // The same skin alone on its own top.
  ASSERT_EQ(run(std::string(ESKIN_BIN) + " simulate " ESKIN_SOURCE_DIR
                "/scenes/neuroskin2.yaml --out " + alone.string(), &log), 0) << log;
  const auto mixed_rows = rows_without_arrival(out / "skin" / "fpga_packets.ndjson");
  const auto alone_rows = rows_without_arrival(alone / "fpga_packets.ndjson");
  ASSERT_GT(alone_rows.size(), 1000u);
  ASSERT_EQ(mixed_rows.size(), alone_rows.size());
  for (size_t i = 0; i < alone_rows.size(); ++i) ASSERT_EQ(mixed_rows[i], alone_rows[i]) << "row " << i;
  std::set<std::string> types;
  for (const auto& r : mixed_rows) types.insert(nlohmann::json::parse(r).at("type"));
  EXPECT_EQ(types, (std::set<std::string>{"amplitudes", "taxels", "spike"}));
}

TEST(SimulateMixed, BadHallFieldIsRejectedBeforeAnythingRuns) {
  const fs::path tmp = fs::path(testing::TempDir());
  const fs::path scene = tmp / "mixed_bad.yaml", out = tmp / "sim_mixed_bad";
  fs::remove_all(out);
  std::string text = slurp(ESKIN_SOURCE_DIR "/scenes/mixed_neuroskin_split.yaml");
  const std::string from = "i2c_address: 0x0C", to = "i2c_address: 200";  // 7-bit addresses end at 127
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), to);
  { std::ofstream(scene) << text; }
  std::string log;
  EXPECT_NE(run(std::string(ESKIN_BIN) + " simulate " + scene.string() + " --out " + out.string(), &log), 0);
  EXPECT_NE(log.find("i2c_address"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

}  // namespace
