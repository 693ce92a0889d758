// Hall section of the scene loader: the shipped Hall scenes load; a scene may
// have a DTMF skin, a Hall skin or both; every malformed Hall scene is
// rejected with FILE:LINE:COL, the field path and what was expected.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sim/hall_world.h"
#include "sim/scene.h"

namespace eskin::sim {
namespace {

const std::string kDir = std::string(ESKIN_SOURCE_DIR) + "/scenes/";

const std::vector<std::string> kBase = {
    "name: h",                                                                            // 1
    "duration_s: 1.0",                                                                    // 2
    "hall:",                                                                              // 3
    "  mlx: {gain_sel: 7, res: 0, osr: 0, dig_filt: 2}",                                  // 4
    "  decode: [baseline, force_curve]",                                                  // 5
    "  cells:",                                                                           // 6
    "    - {name: b0, kind: stack, centre_mm: [0, 0, 18], layer_k_n_per_mm: [1, 4], layer_travel_mm: [1, 1]}",  // 7
    "  magnets:",                                                                         // 8
    "    - {name: m0, shape: cylinder, size_mm: [6, 2], centre_mm: [0, 0, 13], remanence_t: 1.3, cell: b0}",  // 9
    "  sensors:",                                                                         // 10
    "    - {name: s0, position_mm: [0, 0, 0], bus: 0, mux: 0x70, mux_channel: 2, i2c_address: 0x0C}",  // 11
    "    - {name: s1, position_mm: [20, 0, 0], bus: 0, mux: 0x70, mux_channel: 3, i2c_address: 0x0C}",  // 12
    "  stimuli:",                                                                         // 13
    "    - press: {cell: b0, normal_n: 2, t_start_s: 0.1}",                               // 14
    "  locate: {area_mm: [-20, -20, 20, 20]}",                                            // 15
};

std::string with_line(int line, const std::string& text) {
  std::string out;
  for (size_t i = 0; i < kBase.size(); ++i) out += (int(i) + 1 == line ? text : kBase[i]) + "\n";
  return out;
}

TEST(HallScene, BaseParses) {
  const Scene s = parse_scene(with_line(0, ""), "base.yaml");
  EXPECT_FALSE(s.has_skin);
  ASSERT_TRUE(s.has_hall);
  const HallConfig& h = s.hall.config;
  ASSERT_EQ(h.sensors.size(), 2u);
  EXPECT_EQ(h.sensors[1].mux_address, 0x70);  // hex addresses read
  EXPECT_EQ(h.sensors[1].mux_channel, 3);
  EXPECT_EQ(h.sensors[0].i2c_address, 0x0C);
  EXPECT_EQ(h.magnets[0].shape, MagnetShape::Cylinder);
  EXPECT_DOUBLE_EQ(h.magnets[0].size_mm[1], 6.0);
  EXPECT_TRUE(h.wants(HallDecode::ForceCurve));
  ASSERT_EQ(s.hall.presses.size(), 1u);
  EXPECT_EQ(s.hall.presses[0].cell, 0);
}

TEST(HallScene, ShippedScenesLoad) {
  const std::vector<std::pair<const char*, size_t>> scenes = {
      {"hall_000_skin.yaml", 16}, {"hall_001_split.yaml", 1}, {"hall_002_magtac.yaml", 3},
      {"hall_003_metamaterial.yaml", 9}};
  for (const auto& [name, sensors] : scenes) {
    const Scene s = load_scene(kDir + name);
    EXPECT_TRUE(s.has_hall) << name;
    EXPECT_FALSE(s.has_skin) << name;
    EXPECT_EQ(s.hall.config.sensors.size(), sensors) << name;
  }
  EXPECT_EQ(load_scene(kDir + "hall_000_skin.yaml").hall.config.bus_count(), 4);
  EXPECT_EQ(load_scene(kDir + "hall_000_skin.yaml").hall.rolls.size(), 1u);
}

TEST(HallScene, BothSkinsInOneScene) {
  std::string text =
      "duration_s: 0.5\n"
      "skin: {rows: 2, cols: 2, carriers: {rows: [1900, 3300], cols: [5000, 7140]}}\n";
  for (size_t i = 2; i < kBase.size(); ++i) text += kBase[i] + "\n";
  const Scene s = parse_scene(text, "both.yaml");
  EXPECT_TRUE(s.has_skin);
  EXPECT_TRUE(s.has_hall);
  EXPECT_EQ(s.skin.rows, 2);
  EXPECT_EQ(s.hall.config.cells.size(), 1u);
}

struct BadCase {
  const char* what;
  int line;
  std::string text;
  int expect_line;
  std::string field;
  std::vector<std::string> says;
};

class BadHallScene : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadHallScene, RejectedWithFileLineAndField) {
  const BadCase& c = GetParam();
  try {
    parse_scene(with_line(c.line, c.text), "bad.yaml");
    FAIL() << c.what << ": accepted";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), c.expect_line) << c.what << ": " << msg;
    EXPECT_EQ(e.field(), c.field) << c.what << ": " << msg;
    // The device's own legality message (mlx90393_config.h) says "not
    // permitted" instead of "expected".
    if (c.field != "hall.mlx.dig_filt") {
      EXPECT_NE(msg.find("expected"), std::string::npos) << msg;
    }
    for (const auto& s : c.says) EXPECT_NE(msg.find(s), std::string::npos) << s << " in " << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadHallScene,
    ::testing::Values(
        BadCase{"no skin nor hall", 3, "hal:", 3, "hal", {"did you mean 'hall'"}},
        BadCase{"illegal OSR/DIG_FILT", 4, "  mlx: {osr: 0, dig_filt: 1}", 4, "hall.mlx.dig_filt",
                {"not permitted"}},
        BadCase{"unknown decode block", 5, "  decode: [baseline, kriging]", 5, "hall.decode[1]",
                {"got 'kriging'"}},
        BadCase{"unknown cell kind", 7, "    - {name: b0, kind: spring, centre_mm: [0, 0, 1]}", 7,
                "hall.cells[0].kind", {"film, pillar or stack", "'spring'"}},
        BadCase{"field of another kind", 7,
                "    - {name: b0, kind: stack, centre_mm: [0, 0, 1], pillar_mm: 3, layer_k_n_per_mm: [1], layer_travel_mm: [1]}",
                7, "hall.cells[0].pillar_mm", {"no pillar_mm for a stack cell"}},
        BadCase{"layers lock out of order", 7,
                "    - {name: b0, kind: stack, centre_mm: [0, 0, 1], layer_k_n_per_mm: [4, 1], layer_travel_mm: [1, 1]}",
                7, "hall.cells[0].layer_k_n_per_mm[1]", {"lock in order"}},
        BadCase{"travel count", 7,
                "    - {name: b0, kind: stack, centre_mm: [0, 0, 1], layer_k_n_per_mm: [1, 4], layer_travel_mm: [1]}",
                7, "hall.cells[0].layer_travel_mm", {"one travel per layer"}},
        BadCase{"magnet on unknown cell", 9,
                "    - {name: m0, shape: cylinder, size_mm: [6, 2], centre_mm: [0, 0, 13], remanence_t: 1.3, cell: b9}",
                9, "hall.magnets[0].cell", {"(b0)", "'b9'"}},
        BadCase{"remanence zero", 9,
                "    - {name: m0, shape: cylinder, size_mm: [6, 2], centre_mm: [0, 0, 13], remanence_t: 0, cell: b0}",
                9, "hall.magnets[0].remanence_t", {"0 < |Br| <= 2 T"}},
        BadCase{"cylinder size", 9,
                "    - {name: m0, shape: cylinder, size_mm: [6, 2, 1], centre_mm: [0, 0, 13], remanence_t: 1, cell: b0}",
                9, "hall.magnets[0].size_mm", {"[diameter, height]"}},
        BadCase{"bad MLX address", 11,
                "    - {name: s0, position_mm: [0, 0, 0], i2c_address: 0x30}", 11,
                "hall.sensors[0].i2c_address", {"0x0C", "got 48"}},
        BadCase{"bad mux address", 11,
                "    - {name: s0, position_mm: [0, 0, 0], mux: 0x20, mux_channel: 1}", 11,
                "hall.sensors[0].mux", {"got 32"}},
        BadCase{"channel without mux", 11, "    - {name: s0, position_mm: [0, 0, 0], mux_channel: 1}",
                11, "hall.sensors[0].mux_channel", {"only with mux"}},
        BadCase{"address clash on one channel", 12,
                "    - {name: s1, position_mm: [20, 0, 0], bus: 0, mux: 0x70, mux_channel: 2, i2c_address: 0x0C}",
                12, "hall.sensors[1].i2c_address", {"unique on bus 0 mux channel 2"}},
        BadCase{"press past duration", 14, "    - press: {cell: b0, normal_n: 2, t_start_s: 0.9}", 14,
                "hall.stimuli[0].press", {"end by duration_s = 1"}},
        BadCase{"press outside area", 14, "    - press: {at_mm: [50, 0], normal_n: 2}", 14,
                "hall.stimuli[0].press.at_mm", {"inside the skin area"}},
        BadCase{"press without force", 14, "    - press: {cell: b0}", 14,
                "hall.stimuli[0].press.normal_n", {"required"}},
        BadCase{"wrench without plate", 14, "    - wrench: {force_n: [0, 0, -1]}", 14,
                "hall.stimuli[0].wrench", {"rigid_plate: true"}},
        BadCase{"roll of one point", 14, "    - roll: {path_mm: [[0, 0]], speed_mm_s: 10, normal_n: 1}",
                14, "hall.stimuli[0].roll.path_mm", {"at least two"}},
        BadCase{"wrench decode on one sensor", 5, "  decode: [wrench]", 5, "hall.decode",
                {"exactly 3 sensors"}}));

}  // namespace
}  // namespace eskin::sim
