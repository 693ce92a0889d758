// `eskin simulate` on a Hall scene, as a user runs it: seed 001's split cell
// (scenes/hall_001_split.yaml) on the virtual board built for its Hall top
// (one MLX90393 on one I2C bus, hall_baseline, hall_decouple, command path),
// the pty read through host/stream, the report and raw outputs on disk.
// What the run wrote is checked against models the test runs itself:
//  * every HALL_DELTAS record is its HALL_SAMPLES reading minus the
//    geomagnetic baseline the host set by command (quantised here from the
//    scene and the MLX90393's sensitivity), saturated to 16 bits;
//  * every DECOUPLE3 equals hls::HallDecouple run on its frame's delta,
//    with the compensation the golden chain fits (hall::calibrate_decouple,
//    quantised here to the kernel's Q2.14 / 1/64 uT), bit for bit;
//  * the FPGA's force against the truth within 2.5 % of full scale (mean,
//    holds): the HLS chain over the scene gives 1.2 % shear and 0.6 %
//    normal (docs/hall.md) and the FPGA is bit-exact with it (above), so
//    only the noise draw differs; the RTL test bounds 2.3 s of the scene
//    the same way (tests/rtl/hall_top_test.cpp, Seed001);
//  * nothing lost: no link error, no I2C timing violation, every command
//    accepted, one frame per 2053 us conversion;
//  * DRDY -> last byte at the host between one RM read (264 us: the
//    reading's own I2C transfer, docs/hall_fpga.md) and one frame period
//    (2053 us: a slower frame would fall behind the sensor).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "host/hall/hall_chain.h"
#include "eskin/mlx90393_config.h"
#include "hls/hall_decouple.h"
#include "run_command.h"
#include "sim/hall_top_spec.h"
#include "sim/hall_world.h"
#include "sim/scene.h"

namespace {

namespace fs = std::filesystem;
using vboard_test::run;
using vboard_test::slurp;

int16_t sat16(long v) { return int16_t(std::clamp(v, -32768L, 32767L)); }

TEST(SimulateHall, Seed001OnTheVirtualBoardMatchesItsKernelsAndTheTruth) {
  const std::string scene_file = ESKIN_SOURCE_DIR "/scenes/hall_001_split.yaml";
  const fs::path out = fs::path(testing::TempDir()) / "sim_hall_001";
  fs::remove_all(out);
  std::string log;
  ASSERT_EQ(run(std::string(ESKIN_BIN) + " simulate " + scene_file + " --out " + out.string(), &log), 0) << log;
  const nlohmann::json sum = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(sum.at("top"), "hall_top");
  EXPECT_EQ(sum.at("link_errors").get<int>(), 0);
  EXPECT_EQ(sum.at("i2c_violations").get<int>(), 0);
  EXPECT_EQ(sum.at("commands_sent").get<int>(), 4);  // 3 baselines, 1 compensation
  EXPECT_EQ(sum.at("commands_accepted").get<int>(), 4);
  EXPECT_EQ(sum.at("commands_rejected").get<int>(), 0);
  // 4.01 s (the scene and the board's 10 ms tail) at one frame per 2053 us,
  // less the configuration round: 1953 at most.
  EXPECT_GE(sum.at("frames").get<int>(), 1950);
  EXPECT_LE(sum.at("frames").get<int>(), 1954);
  EXPECT_LE(sum.at("incomplete_frames").get<int>(), 1);  // the configuration round
  EXPECT_LT(sum.at("decouple").at("fpga_shear").get<double>(), 0.025);
  EXPECT_LT(sum.at("decouple").at("fpga_normal").get<double>(), 0.025);
  EXPECT_GE(sum.at("decouple").at("fpga_frames").get<int>(), 600);  // ten holds of 150 ms
  const double lat = sum.at("latency_median_us");
  EXPECT_GT(lat, 264.0);
  EXPECT_LT(lat, 2053.0);

  // The kernels' constants, from the scene and the golden calibration.
  const auto sc = eskin::sim::load_scene(scene_file);
  const auto& h = sc.hall.config;
  const auto spec = eskin::sim::hall_top_spec(h);
  const eskin::sim::HallWorld world(sc.hall);
  const auto cal = eskin::hall::calibrate_decouple(world, sc.seed);
  eskin::hls::HallDecoupleConfig cfg;
  for (int a = 0; a < 3; ++a) cfg.gain[a] = spec.dec_gain[a];
  cfg.k1 = int16_t(std::lround(cal.params.k1 * 16384)), cfg.k2 = int16_t(std::lround(cal.params.k2 * 16384));
  cfg.c1 = int32_t(std::lround(cal.params.c1_ut * 64)), cfg.c2 = int32_t(std::lround(cal.params.c2_ut * 64));
  eskin::hls::HallDecouple<0> kernel(cfg);
  long base[3];
  for (int a = 0; a < 3; ++a)
    base[a] = std::lround(h.geomagnetic_ut[size_t(a)] / eskin::mlx90393::sensitivity_uT(h.mlx, a));

  std::istringstream nd(slurp(out / "fpga_packets.ndjson"));
  nlohmann::json sample;  // the frame's one reading (one sensor)
  size_t checked_deltas = 0, checked_decouple = 0;
  bool want_decouple = false;
  eskin::hls::DecoupleToken want;
  for (std::string line; std::getline(nd, line);) {
    const nlohmann::json p = nlohmann::json::parse(line);  // eskin stream's rows
    const std::string type = p.at("type");
    if (type == "hall_samples") {
      ASSERT_FALSE(want_decouple) << "a DECOUPLE3 is missing before t " << p.at("t");
      sample = p;
    } else if (type == "hall_deltas") {
      ASSERT_EQ(p.at("flags"), sample.at("flags"));
      if (p.at("flags").get<int>() & 0x78) continue;  // no data: no delta, no DECOUPLE3
      const char* code[] = {"x", "y", "z"};
      const char* delta[] = {"dx", "dy", "dz"};
      for (int a = 0; a < 3; ++a)
        ASSERT_EQ(p.at(delta[a]).get<int>(),
                  sat16(eskin::mlx90393::code_to_lsb(h.mlx, a, sample.at(code[a]).get<uint16_t>()) - base[a]))
            << "axis " << a << " at t " << p.at("t");
      ++checked_deltas;
      eskin::hls::HallDeltaToken t;
      t.id = p.at("id"), t.t = p.at("t16"), t.flags = p.at("flags");
      for (int a = 0; a < 3; ++a) t.d[a] = p.at(delta[a]).get<int16_t>();
      want_decouple = kernel.push(t, want);
    } else if (type == "hall_decouple") {
      ASSERT_TRUE(want_decouple) << "a DECOUPLE3 the kernel did not emit, t " << p.at("t");
      EXPECT_EQ(p.at("rx").get<int32_t>(), want.rx);
      EXPECT_EQ(p.at("ry").get<int32_t>(), want.ry);
      EXPECT_EQ(p.at("sz").get<int32_t>(), want.sz);
      EXPECT_EQ(p.at("valid").get<int>() != 0, want.valid);
      EXPECT_EQ(p.at("flags").get<int>(), want.flags);
      EXPECT_EQ(p.at("t").get<uint32_t>() & 0xFFFF, want.t);
      want_decouple = false;
      ++checked_decouple;
    }
  }
  EXPECT_GE(checked_deltas, 1950u);
  EXPECT_EQ(checked_decouple, checked_deltas);
  const std::string html = slurp(out / "report.html");
  EXPECT_NE(html.find("Force over time"), std::string::npos);
  EXPECT_EQ(html.find("<script src="), std::string::npos) << "the report must be self-contained";
}

// A Hall scene whose bus cannot carry its sensors is refused before
// anything is built or run, naming the field.
TEST(SimulateHall, BadHallSceneIsRejectedNamingTheField) {
  std::string text = slurp(ESKIN_SOURCE_DIR "/scenes/hall_001_split.yaml");
  const std::string from = "bus: 0, i2c_address: 0x0C";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "bus: 0, i2c_address: 0x99");
  const fs::path scene = fs::path(testing::TempDir()) / "bad_hall.yaml";
  std::ofstream(scene) << text;
  const fs::path out = fs::path(testing::TempDir()) / "bad_hall_out";
  fs::remove_all(out);
  std::string log;
  EXPECT_NE(run(std::string(ESKIN_BIN) + " simulate " + scene.string() + " --out " + out.string(), &log), 0);
  EXPECT_NE(log.find("i2c_address"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out)) << "nothing may be written for a bad scene";
}

}  // namespace
