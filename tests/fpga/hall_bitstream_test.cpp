// host/fpga for scenes with Hall sensors, on the paths before the tools:
// the pins each board gives them (none twice, none the board's own
// constraints use), their assignment and its refusal with the numbers, the
// Hall clock, the constraints written, and the generated core in its board
// wrapper linted by Verilator exactly as the flow hands both to Yosys
// (defines, parameters, files). The tool runs are the bitstream.*_hall_*
// and bitstream.*_mixed_* ctests (tests/fpga/CMakeLists.txt).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "eskin/process.h"
#include "host/fpga/board.h"
#include "host/fpga/core_flows.h"
#include "host/fpga/hall_pins.h"
#include "sim/hall_top_spec.h"
#include "sim/scene.h"

namespace {

using namespace eskin::fpga;
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string param(const std::vector<eskin::hls::VerilogParam>& ps, const std::string& name) {
  for (const auto& p : ps)
    if (p.name == name) return p.value;
  return "<missing>";
}

// The package pins a board's own constraints file places something on.
std::set<std::string> constrained_sites(const Board& b) {
  const std::string text = slurp(fs::path(ESKIN_SOURCE_DIR) / b.constraints);
  const std::regex re(b.family == Family::Ice40 ? R"re(set_io\s.*\s(\d+)\s*$)re"
                                                 : R"re(LOCATE COMP "[^"]+" SITE "(\w+)")re");
  std::set<std::string> sites;
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) {
    std::smatch m;
    if (std::regex_search(line, m, re)) sites.insert(m[1]);
  }
  return sites;
}

// Each board's pool: the iCEBreaker's PMOD1B and PMOD2 (16), the ULX3S's
// J1 gp/gn[4..10] and J2 gp/gn[18..27] (34); no pin twice, none that the
// board's constraints already use (clock, UART, button, LEDs, the ADC).
TEST(HallPins, PoolsAreTheFreeHeaderPins) {
  for (const auto& [name, size] : {std::pair<const char*, size_t>{"icebreaker", 16}, {"ulx3s", 34}}) {
    const Board b = find_board(name);
    const auto& pool = hall_pin_pool(b);
    EXPECT_EQ(pool.size(), size) << name;
    const auto used = constrained_sites(b);
    EXPECT_GE(used.size(), 9u) << name;  // the parse found the board's own pins
    std::set<std::string> seen;
    for (const auto& p : pool) {
      EXPECT_TRUE(seen.insert(p.site).second) << name << " " << p.site << " twice";
      EXPECT_EQ(used.count(p.site), 0u) << name << " " << p.site << " is the board's own";
      EXPECT_FALSE(p.connector.empty());
    }
  }
  // Spot checks against the published files: P1B1 = 43, P2_10 = 18;
  // gp[4] = A7 (J1_13+), gn[27] = E13 (J2_35-).
  const auto& ice = hall_pin_pool(find_board("icebreaker"));
  EXPECT_EQ(ice.front().site, "43");
  EXPECT_EQ(ice.front().connector, "PMOD1B pin 1");
  EXPECT_EQ(ice.back().site, "18");
  EXPECT_EQ(ice.back().connector, "PMOD2 pin 10");
  const auto& ulx = hall_pin_pool(find_board("ulx3s"));
  EXPECT_EQ(ulx.front().site, "A7");
  EXPECT_EQ(ulx.front().connector, "J1 pin 13+ (gp[4])");
  EXPECT_EQ(ulx[14].connector, "J2 pin 13+ (gp[18])");
  EXPECT_EQ(ulx.back().site, "E13");
  EXPECT_EQ(ulx.back().connector, "J2 pin 35- (gn[27])");
}

// Buses first (SCL, SDA of bus 0, then bus 1), then one DRDY per sensor in
// hall_top's slot order; a one-bit port is named without an index (as
// nextpnr sees it).
TEST(HallPins, BusesFirstThenDrdyLines) {
  const HallPins p = assign_hall_pins(find_board("icebreaker"), 2, 2);
  ASSERT_TRUE(p.failure.empty()) << p.failure;
  ASSERT_EQ(p.pins.size(), 8u);
  EXPECT_EQ(p.needed, 8);
  const char* want[][2] = {{"i2c_scl[0]", "43"}, {"i2c_sda[0]", "38"}, {"i2c_scl[1]", "34"},
                           {"i2c_sda[1]", "31"}, {"drdy[0]", "42"},    {"drdy[1]", "36"},
                           {"drdy[2]", "32"},    {"drdy[3]", "28"}};
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(p.pins[i].signal, want[i][0]);
    EXPECT_EQ(p.pins[i].pin.site, want[i][1]);
    EXPECT_EQ(p.pins[i].i2c, i < 4);
  }
  const HallPins one = assign_hall_pins(find_board("ulx3s"), 1, 1);
  ASSERT_EQ(one.pins.size(), 3u);
  EXPECT_EQ(one.pins[0].signal, "i2c_scl");
  EXPECT_EQ(one.pins[2].signal, "drdy");
}

// Seed 000's 4 buses of 4: 8 + 16 = 24 pins, more than the iCEBreaker's 16;
// the ULX3S has 34 (2 x 15 sensors take them all, 5 x 6 need 40).
TEST(HallPins, TooManyAreRefusedWithTheNumbers) {
  const HallPins p = assign_hall_pins(find_board("icebreaker"), 4, 4);
  EXPECT_TRUE(p.pins.empty());
  EXPECT_EQ(p.needed, 24);
  EXPECT_EQ(p.failure,
            "does not fit: the Hall sensors need 24 pins (4 I2C buses x 2 (SCL, SDA) + 16 DRDY "
            "lines), board icebreaker has 16 free (PMOD1B and PMOD2)");
  EXPECT_TRUE(assign_hall_pins(find_board("ulx3s"), 4, 4).failure.empty());
  EXPECT_TRUE(assign_hall_pins(find_board("ulx3s"), 2, 15).failure.empty());
  EXPECT_NE(assign_hall_pins(find_board("ulx3s"), 5, 6).failure.find("need 40 pins"),
            std::string::npos);
}

// hall_top's clock: the iCEBreaker's 12 MHz oscillator itself (PLL 0), or
// any PLL clock asked for; the ULX3S's 30 MHz (25 MHz leaves no 3 Mbaud);
// a clock that is not whole MHz is refused by name.
TEST(HallClock, OscillatorOnTheIcebreakerDefaultElsewhere) {
  const Board ice = find_board("icebreaker");
  const Clocking osc = choose_hall_clock(ice);
  EXPECT_EQ(osc.clk_hz, 12000000);
  EXPECT_EQ(osc.baud, 3000000);
  EXPECT_EQ(param(osc.wrapper_params, "PLL"), "0");
  const Clocking pll = choose_hall_clock(ice, 18000000);
  EXPECT_EQ(param(pll.wrapper_params, "PLL"), "1");
  EXPECT_EQ(param(pll.wrapper_params, "PLL_DIVF"), "47");
  try {
    choose_hall_clock(ice, 12500000);
    FAIL() << "12.5 MHz accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("whole number of MHz"), std::string::npos) << e.what();
  }
  const Clocking ulx = choose_hall_clock(find_board("ulx3s"));
  EXPECT_EQ(ulx.clk_hz, 30000000);
  EXPECT_EQ(param(ulx.wrapper_params, "CLKI_DIV"), "5");
  EXPECT_EQ(param(ulx.wrapper_params, "PLL"), "<missing>");
  EXPECT_THROW(choose_hall_clock(find_board("ulx3s"), 12000000), std::invalid_argument);
}

// The constraints: the board's own first, then each Hall pin with its
// connector; bus lines with the weak pull-up, DRDY without (iCE40) or
// pulled down (ECP5); the file says that real buses need their own.
TEST(HallConstraints, PullUpsOnTheBusLinesAndTheConnectorOnEachPin) {
  const Board ice = find_board("icebreaker");
  const std::string base = slurp(fs::path(ESKIN_SOURCE_DIR) / ice.constraints);
  const std::string pcf = hall_constraints(ice, base, assign_hall_pins(ice, 1, 3));
  EXPECT_EQ(pcf.rfind(base, 0), 0u);
  EXPECT_NE(pcf.find("set_io -nowarn -pullup yes i2c_scl 43  # PMOD1B pin 1\n"), std::string::npos) << pcf;
  EXPECT_NE(pcf.find("set_io -nowarn drdy[2] 42  # PMOD1B pin 7\n"), std::string::npos) << pcf;
  EXPECT_NE(pcf.find("needs its own pull-ups"), std::string::npos);
  const Board ulx = find_board("ulx3s");
  const std::string lpf = hall_constraints(ulx, "", assign_hall_pins(ulx, 2, 1));
  EXPECT_NE(lpf.find("LOCATE COMP \"i2c_scl[0]\" SITE \"A7\";  # J1 pin 13+ (gp[4])\n"),
            std::string::npos) << lpf;
  EXPECT_NE(lpf.find("IOBUF PORT \"i2c_sda[1]\" PULLMODE=UP IO_TYPE=LVCMOS33 DRIVE=4;"),
            std::string::npos) << lpf;
  EXPECT_NE(lpf.find("IOBUF PORT \"drdy[1]\" PULLMODE=DOWN IO_TYPE=LVCMOS33;"), std::string::npos);
}

struct Case {
  const char* board;
  const char* scene;
};

class HallBuild : public ::testing::TestWithParam<Case> {};

// What the flow writes for a Hall or mixed scene, up to the tools: the
// core module and the wrapper lint clean under Verilator -Wall with the
// flow's defines and wrapper parameters; every Hall pin in the constraints;
// hall_top's parameters those of the virtual board's derivation at the
// build's clock.
TEST_P(HallBuild, GeneratedCoreInItsWrapperLintsCleanAndEveryPinIsPlaced) {
  const Case c = GetParam();
  const Board b = find_board(c.board);
  const auto scene = eskin::sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/" + c.scene);
  const fs::path out = fs::temp_directory_path() / (std::string("eskin_hall_build_") + c.board +
                                                    "_" + fs::path(c.scene).stem().string());
  fs::remove_all(out);
  FlowOptions opt;
  opt.source_dir = ESKIN_SOURCE_DIR;
  opt.out_dir = out.string();
  FlowReport r;
  r.core = scene_core(scene);
  ToolRun t;
  ASSERT_TRUE(prepare_hall_build(b, scene, opt, r, t)) << r.failure;
  EXPECT_EQ(t.top, b.hall_wrapper);
  // The Hall parameters at the build's clock (mixed: the DTMF one's).
  const auto spec = eskin::sim::hall_top_spec(scene.hall.config, double(r.clk_hz));
  EXPECT_EQ(param(r.params, "CLK_HZ"), std::to_string(r.clk_hz));
  EXPECT_EQ(param(r.params, "NB"), std::to_string(spec.nb));
  EXPECT_EQ(param(r.params, "CONV_CYC"), std::to_string(spec.conv_cyc));
  if (r.core == Core::Mixed) {
    EXPECT_EQ(r.clk_hz, r.spec.clk_hz);
  }
  // Every pin of the report in the constraints file.
  const std::string pins = slurp(t.constraints);
  for (const auto& p : r.hall.pins.pins)
    EXPECT_NE(pins.find(p.signal), std::string::npos) << p.signal;
  std::vector<std::string> cmd{"verilator", "--lint-only", "-Wall", "-y", ESKIN_SOURCE_DIR "/rtl",
                               "--top-module", t.top};
  for (const auto& d : t.defines) cmd.push_back("+define+" + d);
  for (const auto& p : t.params) cmd.push_back("-G" + p.name + "=" + p.value);
  cmd.push_back(std::string(ESKIN_SOURCE_DIR) + "/rtl/" + t.top + ".v");
  for (const auto& f : t.reads) cmd.push_back(f);
  const std::string log = (std::filesystem::temp_directory_path() /
                           ("hall_lint_" + t.top + "_" + std::to_string(::getpid()) + ".log")).string();
  EXPECT_EQ(eskin::run_logged(cmd, log), 0) << eskin::printable_command(cmd) << "\n" << slurp(log);
  std::filesystem::remove(log);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, HallBuild,
    ::testing::Values(Case{"icebreaker", "hall_002_magtac.yaml"},
                      Case{"icebreaker", "hall_003_metamaterial.yaml"},
                      Case{"icebreaker", "mixed_neuroskin_split.yaml"},
                      Case{"ulx3s", "hall_000_skin.yaml"}, Case{"ulx3s", "hall_001_split.yaml"},
                      Case{"ulx3s", "mixed_neuroskin_split.yaml"}),
    [](const auto& info) {
      return std::string(info.param.board) + "_" +
             std::regex_replace(fs::path(info.param.scene).stem().string(), std::regex("\\W"), "");
    });

// Seed 000 on the iCEBreaker stops before anything is written.
TEST(HallBuild, TooFewPinsStopBeforeAnyFile) {
  const auto scene = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/hall_000_skin.yaml");
  const fs::path out = fs::temp_directory_path() / "eskin_hall_build_toofew";
  fs::remove_all(out);
  FlowOptions opt;
  opt.source_dir = ESKIN_SOURCE_DIR;
  opt.out_dir = out.string();
  FlowReport r;
  r.core = scene_core(scene);
  ToolRun t;
  EXPECT_FALSE(prepare_hall_build(find_board("icebreaker"), scene, opt, r, t));
  EXPECT_NE(r.failure.find("need 24 pins"), std::string::npos) << r.failure;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
