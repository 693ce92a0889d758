// host/fpga: the boards' clocks, the parsers of nextpnr's output, the scale
// table's scenes and CSV, and the core's clock limits. The tool runs
// themselves are the bitstream.* ctests (tests/fpga/CMakeLists.txt).
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <set>
#include <string>

#include "ucode/dtmf_engine_image.h"
#include "eskin/dtmf_top_plan.h"
#include "host/fpga/board.h"
#include "host/fpga/flow.h"
#include "host/fpga/scale_table.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"

namespace {

using namespace eskin::fpga;

std::string param(const std::vector<eskin::hls::VerilogParam>& ps, const std::string& name) {
  for (const auto& p : ps)
    if (p.name == name) return p.value;
  return "<missing>";
}

// The default 30 MHz must use the dividers that Lattice's PLL calculator
// (ecppll from prjtrellis, run once by hand: `ecppll -i 25 -o 30`) gives:
// CLKI_DIV 5, CLKFB_DIV 6, CLKOP_DIV 20. rtl/board_ulx3s.v has the same
// defaults.
TEST(BoardClocks, Ulx3sDefaultIs30MHzWithEcppllDividers) {
  const Board b = find_board("ulx3s");
  const Clocking c = choose_clock(b, 0);
  EXPECT_EQ(c.clk_hz, 30000000);
  EXPECT_EQ(c.baud, 3000000);
  EXPECT_EQ(param(c.wrapper_params, "CLKI_DIV"), "5");
  EXPECT_EQ(param(c.wrapper_params, "CLKFB_DIV"), "6");
  EXPECT_EQ(param(c.wrapper_params, "CLKOP_DIV"), "20");
}

// Every clock offered is exact: 25 MHz * FB / REF, phase detector >= 3.125
// MHz, VCO in 400..800 MHz, and a whole number of clocks per UART bit.
TEST(BoardClocks, EveryUlx3sClockIsExactAndLegal) {
  const auto clocks = board_clocks(find_board("ulx3s"));
  ASSERT_GT(clocks.size(), 20u);
  for (const auto& c : clocks) {
    const long ref = std::stol(param(c.wrapper_params, "CLKI_DIV"));
    const long fb = std::stol(param(c.wrapper_params, "CLKFB_DIV"));
    const long op = std::stol(param(c.wrapper_params, "CLKOP_DIV"));
    EXPECT_EQ(25000000L * fb, c.clk_hz * ref) << c.clk_hz;
    EXPECT_LE(ref, 8);
    EXPECT_GE(c.clk_hz * op, 400000000L);
    EXPECT_LE(c.clk_hz * op, 800000000L);
    EXPECT_EQ(c.clk_hz % c.baud, 0) << c.clk_hz;
  }
}

// 12 MHz cannot be made from 25 MHz with REF <= 8 (12/25 needs REF 25;
// ecppll's nearest is 12.5 MHz), so asking for it names the clocks there are.
TEST(BoardClocks, UnmakeableClockIsRejectedWithTheList) {
  try {
    choose_clock(find_board("ulx3s"), 0, 12000000);
    FAIL() << "12 MHz accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--clk-mhz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("30 MHz"), std::string::npos) << e.what();
  }
}

// The iCEBreaker's default is the lead's 18 MHz = 12 MHz x 3/2 with the
// dividers `icepll -i 12 -o 18` gives (DIVR 0, DIVF 47, DIVQ 5, FILTER_RANGE
// 1: VCO 576 MHz), rtl/board_icebreaker.v's defaults; and every clock
// offered has icepll's dividers (icestorm's own calculator, run here).
TEST(BoardClocks, IcebreakerClocksAreIcepllsDividers) {
  const Board b = find_board("icebreaker");
  const Clocking c = choose_clock(b, 0);
  EXPECT_EQ(c.clk_hz, 18000000);
  EXPECT_EQ(c.baud, 3000000);
  EXPECT_EQ(param(c.wrapper_params, "PLL_DIVR"), "0");
  EXPECT_EQ(param(c.wrapper_params, "PLL_DIVF"), "47");
  EXPECT_EQ(param(c.wrapper_params, "PLL_DIVQ"), "5");
  EXPECT_EQ(param(c.wrapper_params, "PLL_FILTER_RANGE"), "1");
  const auto clocks = board_clocks(b);
  ASSERT_GT(clocks.size(), 10u);
  // 16 and 17 MHz are not 12 MHz x (DIVF + 1) / 2^DIVQ with the VCO in
  // range, and 16.5 MHz divides into no baud rate: 18 MHz is the lowest.
  EXPECT_EQ(clocks.front().clk_hz, 18000000);
  for (const auto& k : clocks) {
    EXPECT_EQ(k.clk_hz % k.baud, 0) << k.clk_hz;
    const std::string cmd = "icepll -i 12 -o " + std::to_string(k.clk_hz / 1e6) + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string out;
    char buf[256];
    while (fgets(buf, sizeof buf, p)) out += buf;
    ASSERT_EQ(pclose(p), 0) << cmd << ": " << out;
    for (const char* f : {"DIVR", "DIVF", "DIVQ", "FILTER_RANGE"}) {
      const std::regex re(std::string("\n") + f + R"(:\s+(\d+))");
      std::smatch m;
      ASSERT_TRUE(std::regex_search(out, m, re)) << out;
      EXPECT_EQ(param(k.wrapper_params, std::string("PLL_") + f), m[1].str()) << k.clk_hz << " " << f;
    }
  }
  EXPECT_THROW(choose_clock(b, 0, 13000000), std::invalid_argument);
  EXPECT_THROW(find_board("icebreaker", "85k"), std::invalid_argument);
  EXPECT_EQ(find_board("ulx3s", "25k").device, "25k");
  EXPECT_THROW(find_board("ulx4s"), std::invalid_argument);
}

// The lines nextpnr-ice40 0.4 printed for a design 59 LCs too big (the
// board wrapper around today's dtmf_top): the block after "Device
// utilisation:", whatever follows.
TEST(NextpnrParse, UtilisationFromTheLogOfAFailedPlacement) {
  const std::string log =
      "Info: Annotating ports with timing budgets for target frequency 12.00 MHz\n"
      "Info: Device utilisation:\n"
      "Info: \t         ICESTORM_LC:  5339/ 5280   101%\n"
      "Info: \t        ICESTORM_RAM:    21/   30    70%\n"
      "Info: \t        ICESTORM_DSP:     4/    8    50%\n"
      "\n"
      "Info: Placed 9 cells based on constraints.\n"
      "ERROR: Failed to expand region (0, 0) |_> (25, 31) of 5339 ICESTORM_LCs\n";
  const auto u = parse_nextpnr_utilisation(log);
  ASSERT_EQ(u.size(), 3u);
  EXPECT_EQ(u[0].name, "ICESTORM_LC");
  EXPECT_EQ(u[0].used, 5339);
  EXPECT_EQ(u[0].available, 5280);
  EXPECT_EQ(u[2].name, "ICESTORM_DSP");
  EXPECT_EQ(u[2].used, 4);
}

TEST(NextpnrParse, ReportJsonGivesResourcesAndEveryClock) {
  FlowReport r;
  parse_nextpnr_report(
      R"({"utilization": {"TRELLIS_COMB": {"available": 83640, "used": 4502},
                          "MULT18X18D": {"available": 156, "used": 4}},
          "fmax": {"$glbnet$clk": {"achieved": 43.2, "constraint": 30},
                   "clk_25mhz$TRELLIS_IO_IN": {"achieved": 400.0, "constraint": 25}}})",
      r);
  ASSERT_NE(r.resource("TRELLIS_COMB"), nullptr);
  EXPECT_EQ(r.resource("TRELLIS_COMB")->used, 4502);
  EXPECT_EQ(r.resource("MULT18X18D")->available, 156);
  ASSERT_EQ(r.clocks.size(), 2u);
  EXPECT_EQ(r.resource("DP16KD"), nullptr);
}

// The scale table's 16x16 scene: window 128 (the shortest power of two
// whose bins hold 32 carriers below Nyquist), carriers on the odd bins
// 1..63 (inc = bin << 25), so no demixing: 32 DFT channels, ACC_W 20
// (12 + 1 + log2 128).
TEST(ScaleTable, SixteenBySixteenSceneOnBinCentres) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto sc = scale_scene(base, 16, 35000.0);
  EXPECT_EQ(sc.decoder.window, 128);
  const auto plan = eskin::hls::make_dtmf_top_plan(eskin::sim::dtmf_top_spec(sc));
  EXPECT_FALSE(plan.spec.demix);
  ASSERT_EQ(plan.ks, 32);
  EXPECT_EQ(plan.acc_w, 20);
  for (int k = 0; k < 32; ++k) EXPECT_EQ(plan.inc[size_t(k)], uint32_t(2 * k + 1) << 25) << k;
}

TEST(ScaleTable, CsvRoundTripAndFitHint) {
  ScaleRow a;
  a.target = "up5k";
  a.board = "icebreaker";
  a.device = "up5k";
  a.sample_hz = 35000;
  a.rows = a.cols = 2;
  a.window = 32;
  a.step = 1;
  a.clk_hz = 12000000;
  a.fits = a.meets_timing = true;
  a.logic_used = 4000;
  a.logic_available = 5280;
  a.fmax_mhz = 17.25;
  ScaleRow b = a;
  b.rows = b.cols = 3;
  b.fits = false;
  b.failure = "does not fit: ICESTORM_LC 5300/5280 (100.4 %), \"quoted\"";
  ScaleRow c = a;
  c.sample_hz = 1e6;
  c.rows = c.cols = 4;  // passes at the other rate only
  c.adc_clk_hz = 40000000;  // with the ADC on its own clock
  c.seed = 3;               // placed at the third seed tried
  c.engine = {true, true, true};  // barrel shifter, the neuron unit's lanes
  const auto rows = parse_scale_csv(scale_csv({a, b, c}));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_TRUE(rows[2].engine == c.engine);
  EXPECT_TRUE(rows[0].engine == a.engine);
  EXPECT_NE(scale_csv({c}).find(",barrel,lanes,"), std::string::npos) << scale_csv({c});
  EXPECT_EQ(rows[0].adc_clk_hz, 0);
  EXPECT_EQ(rows[2].adc_clk_hz, 40000000);
  EXPECT_EQ(rows[0].seed, 1);
  EXPECT_EQ(rows[2].seed, 3);
  EXPECT_NE(scale_markdown(rows).find("17.2 MHz (seed 3)"), std::string::npos)
      << scale_markdown(rows);
  EXPECT_EQ(rows[1].failure, b.failure);
  EXPECT_EQ(rows[0].logic_used, 4000);
  EXPECT_DOUBLE_EQ(rows[0].fmax_mhz, 17.25);
  const std::string hint = fit_hint(rows, "icebreaker", "up5k", 35000);
  EXPECT_NE(hint.find("up to 2x2"), std::string::npos) << hint;
  EXPECT_NE(fit_hint(rows, "icebreaker", "up5k", 900000).find("up to 4x4"), std::string::npos);
  EXPECT_NE(fit_hint(rows, "ulx3s", "85k", 35000).find("no entry"), std::string::npos);
  EXPECT_THROW(parse_scale_csv("target,nonsense\n"), std::runtime_error);
  // A tool's multi-line error stays one CSV row (Yosys's $error text ends
  // in a newline before the flow's "(log: ...)").
  ScaleRow e = b;
  e.failure = "yosys failed: ERROR: x\n (log: y)";
  const auto one = parse_scale_csv(scale_csv({e}));
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].failure, "yosys failed: ERROR: x  (log: y)");
  // A partial run replaces only the target and rate it measured.
  ScaleRow d = a;
  d.rows = d.cols = 8;
  const auto merged = merge_scale_rows(rows, {d});
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[0].sample_hz, 1e6);
  EXPECT_EQ(merged[1].rows, 8);
  const std::string md = scale_markdown(rows);
  EXPECT_NE(md.find("| up5k | 35 kS/s | 2x2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 12 MHz (ADC 40) |"), std::string::npos) << md;
}

// A size is in the table when one of its builds passes: 3x3 misses timing
// with the board's engine and passes with the neuron unit, 4x4 fails with
// both, and the table names each engine's reason for 4x4. The engine is a
// CSV column, checked by the parser.
TEST(ScaleTable, ASizePassesWithAnyOfItsEngines) {
  ScaleRow a;
  a.target = "up5k";
  a.board = "icebreaker";
  a.device = "up5k";
  a.sample_hz = 35000;
  a.rows = a.cols = 3;
  a.clk_hz = 27000000;
  a.engine = {true, false};
  a.fits = true;
  a.failure = "misses timing: 21.0 MHz";
  ScaleRow b = a;
  b.engine = {false, true};
  b.clk_hz = 18000000;
  b.meets_timing = true;
  b.failure.clear();
  ScaleRow c = a, d = b;
  c.rows = c.cols = d.rows = d.cols = 4;
  d.meets_timing = d.fits = false;
  d.failure = "does not fit: ICESTORM_LC 5446/5280";
  const auto rows = parse_scale_csv(scale_csv({a, b, c, d}));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_TRUE(rows[1].engine == (EngineVariant{false, true}));
  EXPECT_TRUE(rows[2].engine == (EngineVariant{true, false}));
  const std::string md = scale_markdown(rows);
  EXPECT_NE(md.find("| up5k | 35 kS/s | 3x3 | 6 | 0 | serial shifter, neuron unit | 18 MHz |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("4x4: barrel shifter, engine neurons: misses timing: 21.0 MHz; serial "
                    "shifter, neuron unit: does not fit: ICESTORM_LC 5446/5280"),
            std::string::npos)
      << md;
  std::string csv = scale_csv({a});
  csv.replace(csv.find("barrel,engine"), 13, "barrel,neurons");
  EXPECT_THROW(parse_scale_csv(csv), std::runtime_error);
}

// The second engine the table tries when the board's misses timing. Bound:
// the frame engine's clocks a frame (instruction-set model, stress
// signals; docs/fpga.md): 8x8 at 35 kS/s takes 26 406 with the barrel
// shifter and microcode neurons (so 27 MHz on the iCEBreaker, which the
// UP5K does not reach), 41 843 bit-serial (slower still), 16 670
// bit-serial with the unit (18 MHz): the smallest that keeps up at a
// slower clock. On the ULX3S the board's engine (barrel + neuron lanes)
// is the fastest, so nothing else helps a 24x24 skin that missed its
// clock.
TEST(ScaleTable, SlowerClockVariantIsTheSmallestThatKeepsUp) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const Board ice = find_board("icebreaker");
  const auto sc = scale_scene(base, 8, 35000.0);
  const auto v = slower_clock_variant(ice, sc, {true, false}, 27000000);
  ASSERT_TRUE(v.has_value());
  EXPECT_TRUE(v->engine == (EngineVariant{false, true})) << variant_name(v->engine);
  EXPECT_EQ(variant_name(v->engine), "serial shifter, neuron unit");
  EXPECT_EQ(v->clk_hz, 18000000);
  EXPECT_LE(v->engine_clocks, 18000);  // 35 samples of 514 clocks at 18 MHz: 17 990
  const Board ulx = find_board("ulx3s", "85k");
  const auto sc24 = scale_scene(base, 24, 35000.0);
  const CoreClock lanes24 = choose_core_clock(ulx, sc24, LoadPolicy::Stress, 0, -1, -1, true, 0);
  EXPECT_GT(lanes24.plan.spec.neuron_lanes, 0);
  EXPECT_FALSE(
      slower_clock_variant(ulx, sc24, {true, true, true}, lanes24.clocking.clk_hz).has_value());
  // The same for a user's failed build (eskin bitstream's hint): it names
  // the options; a build that failed for area gets none.
  FlowReport r;
  r.ran_tools = r.fits = true;
  r.clk_hz = 27000000;
  r.spec.engine_fast_shift = true;
  r.policy = LoadPolicy::Stress;
  const std::string hint = slower_engine_hint(ice, sc, r);
  EXPECT_NE(hint.find("keeps up at 18 MHz"), std::string::npos) << hint;
  EXPECT_NE(hint.find("--engine-shifter serial --neurons unit"), std::string::npos) << hint;
  r.fits = false;
  EXPECT_EQ(slower_engine_hint(ice, sc, r), "");
}
// The packets are paced for the link the chosen clock gives. A 26x26 skin
// at 35 kS/s on the ULX3S (its engine with the neuron lanes fits a frame
// at 35 MHz) runs at 35 MHz, whose exact UART rate
// is 1 Mbaud (35 MHz is no multiple of 2 or 3 MHz); the plan thins the
// amplitude and taxel packets so that 1.5 x their bytes per frame fit the
// link (common/eskin/dtmf_top_plan.h): 1.5 x ((10 + 2 x 52 + 2) + (10 + 2 + 2 x
// 676 + 2)) = 2223 bytes against 100 a 1 ms frame at 1 Mbaud (10 bits a
// byte): every 23rd frame (ceil 22.2); planned for 3 Mbaud (300 bytes) it
// would be every 8th, which would overrun the 1 Mbaud line. (Before it the
// 24x24 and the 18x18 skins showed it, until their engines got faster.) The 16x16 1 MS/s build of
// tests/rtl/dtmf_top_test.cpp is planned at its clock's 2 Mbaud (40 MHz),
// so it is this flow's build. (The frame engine asked for, datapath 0: left
// to the board, these skins take the streaming datapath, whose control
// plane keeps up at 30 MHz.)
TEST(CoreClock, PacketsArePlannedForTheChosenClocksBaudRate) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const CoreClock c = choose_core_clock(find_board("ulx3s"), scale_scene(base, 26, 35000.0),
                                        LoadPolicy::Stress, 0, -1, -1, true, 0);
  ASSERT_TRUE(c.budget.ok()) << c.budget.problems.front();
  EXPECT_EQ(c.clocking.clk_hz, 35000000);
  EXPECT_EQ(c.clocking.baud, 1000000);
  EXPECT_EQ(c.plan.spec.baud, 1000000);
  EXPECT_EQ(c.plan.decim_tax, 23);
  EXPECT_EQ(c.plan.decim_amp, 23);
  const auto params =
      eskin::hls::dtmf_top_params(c.plan, eskin::hls::dtmf_engine_image(c.plan), "", "");
  EXPECT_EQ(param(params, "BAUD"), "1000000");
  // 30x30 at 35 kS/s: its engine sets the clock (about 46 000 clocks a
  // 35-sample frame of 1 ms: 50 MHz, far above the ADC's 1 MHz and the
  // DFT's), and the flow's messages give that figure.
  const CoreClock big = choose_core_clock(find_board("ulx3s"), scale_scene(base, 30, 35000.0),
                                          LoadPolicy::Stress, 0, -1, -1, true, 0);
  EXPECT_GT(big.engine_clocks, 40000);
  EXPECT_EQ(big.core_min_hz, big.engine_clocks * 1000);
  const std::string why = eskin::hls::dtmf_top_min_clock_reason(big.plan, big.engine_clocks);
  EXPECT_NE(why.find(fmt::format("the frame engine's {} clocks a frame of 35 samples {:.1f} MHz",
                                 big.engine_clocks, big.engine_clocks / 1000.0)),
            std::string::npos) << why;
  // The default scene's ULX3S clock (30 MHz) is a 3 Mbaud one: one pass.
  const CoreClock d = choose_core_clock(find_board("ulx3s"), base, LoadPolicy::Scene);
  EXPECT_EQ(d.clocking.baud, 3000000);
  EXPECT_EQ(d.plan.spec.baud, 3000000);
}

}  // namespace

namespace {

// The engine's barrel shifter is the ECP5 board's always, and the UP5K's
// (whose LCs are scarce) only when its bit-serial engine would need more
// than the board's 18 MHz default. Bound: the same skin under the same
// stress signals needs fewer engine clocks with the shifter (every shift
// of n > 1 bits saves n - 1 clocks and nothing gets slower), so its minimum
// core clock is lower. A 4x4 35 kS/s skin's bit-serial engine fits 18 MHz
// (about 13 000 clocks a millisecond), so the UP5K keeps the serial one; a
// 6x6's needs about 25 000 (25 MHz, above the UP5K's reach of about 21), so
// the UP5K takes the shifter, and the 6x6 must then fit its 18 MHz (at most
// 18 000 clocks). The user's choice (fast_shift 0) stands. (The neuron unit
// is off throughout: the shifter alone is measured.)
// The passes that plan the packets for the chosen clock's UART cannot step
// down from clock to clock. A 12x12 skin at 35 kS/s on the ULX3S with the
// bit-serial shifter and the neuron unit used to: planned for 3 Mbaud it
// took a 2 Mbaud clock, planned for 2 Mbaud a 1 Mbaud one, and the flow
// threw (a plan for a faster link than the clock's). Now a pass after the
// first only takes clocks at least as fast as its plan's link, so it ends
// on one whose UART carries the packets it was planned for.
TEST(CoreClock, PassesDoNotStepDownToASlowerLink) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto sc = scale_scene(base, 12, 35000.0);
  const Board ulx = find_board("ulx3s");
  CoreClock c;
  ASSERT_NO_THROW(c = choose_core_clock(ulx, sc, LoadPolicy::Stress, 0, 0, 1));
  EXPECT_TRUE(c.budget.ok());
  // Its packets were planned for this clock's rate or a slower one: the
  // plan at the clock's own rate thins them at least as much.
  auto at_clock = c.plan.spec;
  const auto replanned = eskin::hls::make_dtmf_top_plan(at_clock);
  EXPECT_GE(c.plan.decim_tax, replanned.decim_tax);
  EXPECT_GE(c.plan.decim_amp, replanned.decim_amp);
  std::printf("12x12 serial + unit on the ULX3S: %ld engine clocks, %.0f MHz, %ld baud\n",
              c.engine_clocks, c.clocking.clk_hz / 1e6, c.clocking.baud);
}

TEST(CoreClock, BarrelShifterOnTheUlx3sAndOnTheUp5kWhenNeeded) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto ice_board = find_board("icebreaker");
  const auto ice4 = choose_core_clock(ice_board, scale_scene(base, 4, 35000.0), LoadPolicy::Stress, 0, -1, 0);
  EXPECT_FALSE(ice4.plan.spec.engine_fast_shift);
  EXPECT_LE(ice4.core_min_hz, ice_board.default_clk_hz);
  const auto sc = scale_scene(base, 6, 35000.0);
  const CoreClock serial = choose_core_clock(ice_board, sc, LoadPolicy::Stress, 0, 0, 0);
  const CoreClock ice = choose_core_clock(ice_board, sc, LoadPolicy::Stress, 0, -1, 0);
  const CoreClock ecp = choose_core_clock(find_board("ulx3s"), sc, LoadPolicy::Stress, 0, -1, 0);
  EXPECT_FALSE(serial.plan.spec.engine_fast_shift);
  EXPECT_TRUE(ice.plan.spec.engine_fast_shift);
  EXPECT_TRUE(ecp.plan.spec.engine_fast_shift);
  std::printf("6x6 at 35 kS/s, engine clocks per frame (stress + command): bit-serial %ld, "
              "barrel %ld; minimum clocks %.1f / %.1f MHz\n",
              serial.engine_clocks, ice.engine_clocks, serial.core_min_hz / 1e6, ice.core_min_hz / 1e6);
  EXPECT_GT(serial.core_min_hz, ice_board.default_clk_hz);
  EXPECT_LT(ice.engine_clocks, serial.engine_clocks);
  EXPECT_LE(ice.engine_clocks, 18000);
  EXPECT_EQ(ice.clocking.clk_hz, ice_board.default_clk_hz);
  EXPECT_EQ(ecp.engine_clocks, ice.engine_clocks);  // the same engine
  EXPECT_EQ(param(eskin::hls::dtmf_top_params(ice.plan, eskin::hls::dtmf_engine_image(ice.plan), "", ""),
                  "ENGINE_FAST_SHIFT"),
            "1");
}

// The neuron unit is the ULX3S's always, the UP5K's when needed. Bound on
// the ULX3S: an 8x8 35 kS/s skin (128 neurons) under the stress signals,
// with the barrel shifter either way; the izhikevich_layer routine and its
// loop take at least 104 clocks a neuron and the unit's loop at most 28
// (tests/ucode/dtmf_ucode_test.cpp), so the unit saves at least 128 x 76 =
// 9 728 clocks a frame; with the unit the ULX3S's 30 MHz default carries
// it (30 000 clocks a frame). (The frame engine asked for: datapath 0.)
TEST(CoreClock, Ulx3sHasTheNeuronUnit) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto sc = scale_scene(base, 8, 35000.0);
  const CoreClock engine =
      choose_core_clock(find_board("ulx3s"), sc, LoadPolicy::Stress, 0, -1, 0, true, 0);
  const CoreClock unit = choose_core_clock(find_board("ulx3s"), sc, LoadPolicy::Stress, 0, -1, -1, true, 0);
  EXPECT_FALSE(engine.plan.spec.neuron_unit);
  EXPECT_TRUE(unit.plan.spec.neuron_unit);
  std::printf("8x8 at 35 kS/s, barrel shifter, longest stress frame: neurons on the engine %llu "
              "clocks, on the unit %llu; minimum clocks %.1f / %.1f MHz\n",
              (unsigned long long)engine.load.stress_clocks,
              (unsigned long long)unit.load.stress_clocks, engine.core_min_hz / 1e6,
              unit.core_min_hz / 1e6);
  EXPECT_LE(unit.load.stress_clocks + 128 * 76, engine.load.stress_clocks);
  EXPECT_LE(unit.engine_clocks, 30000);
  EXPECT_EQ(unit.clocking.clk_hz, 30000000);
  EXPECT_EQ(param(eskin::hls::dtmf_top_params(unit.plan, eskin::hls::dtmf_engine_image(unit.plan), "", ""),
                  "NEURON_UNIT"),
            "1");
}

// The ULX3S's neuron lanes (Board::neuron_lanes) number 2^11 neurons: a
// 32x32 skin (2 x 1024) gets them, a 34x34 one (2 x 1156) the unit alone;
// asked for (`--neurons lanes`, 2), the 34x34 plan is refused with the
// limit named, not built without them.
TEST(CoreClock, NeuronLanesUpTo1024Taxels) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const Board ulx = find_board("ulx3s", "85k");
  EXPECT_EQ(neuron_lanes_for(ulx, -1, 32 * 32), 5);
  EXPECT_EQ(neuron_lanes_for(ulx, -1, 34 * 34), 0);
  EXPECT_EQ(neuron_lanes_for(ulx, 1, 32 * 32), 0);
  EXPECT_EQ(neuron_lanes_for(find_board("icebreaker"), -1, 8 * 8), 0);
  EXPECT_EQ(neuron_lanes_for(find_board("icebreaker"), 2, 8 * 8), 5);
  try {
    choose_core_clock(ulx, scale_scene(base, 34, 35000.0), LoadPolicy::Stress, 0, -1, 2);
    ADD_FAILURE() << "a 34x34 skin was planned with neuron lanes";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("neuron_lanes: expected 0, or 5..8 with the neuron unit "
                                         "and at most 1024 taxels, got 5 for 1156 taxels"),
              std::string::npos)
        << e.what();
  }
}

// The iCEBreaker's engine when needed (Board::engine_when_needed): the
// first of bit-serial, barrel, serial + unit, barrel + unit whose core
// keeps up at 18 MHz (or the clock asked for) with its measured load and
// its static bound within 90 % of the frame (which run_flow checks), else
// the fastest; an option the user gives stays. The bounds are the engines'
// own minimum clocks, measured here by the same instruction-set model,
// and their bounds (ucode/dtmf_frame_bound.h): an 8x8 skin at 35 kS/s
// needs more than 18 MHz with the barrel shifter alone; the bit-serial
// shifter with the unit keeps up at 18 MHz with its measured load and
// with its bound (every neuron spiking, the longest SET_WEIGHT) within
// 90 % of the frame, so the board takes it, the smaller engine, at its
// 18 MHz clock. A 9x9 skin's serial + unit keeps up by measurement but
// not by its bound: the board takes barrel + unit.
TEST(CoreClock, IcebreakerTakesTheEngineItNeeds) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const Board ice = find_board("icebreaker");
  const auto sc8 = scale_scene(base, 8, 35000.0);
  const CoreClock barrel = choose_core_clock(ice, sc8, LoadPolicy::Stress, 0, 1, 0);
  const CoreClock serial_unit = choose_core_clock(ice, sc8, LoadPolicy::Stress, 0, 0, 1);
  EXPECT_GT(barrel.core_min_hz, ice.default_clk_hz);
  EXPECT_LE(serial_unit.core_min_hz, ice.default_clk_hz);
  const CoreClock chosen = choose_core_clock(ice, sc8, LoadPolicy::Stress);
  const auto within = [](const CoreClock& c) {
    return long(c.bound.total()) * 10 <= 9L * c.budget.frame_clocks;
  };
  EXPECT_TRUE(within(serial_unit));
  EXPECT_FALSE(chosen.plan.spec.engine_fast_shift);
  EXPECT_TRUE(chosen.plan.spec.neuron_unit);
  EXPECT_TRUE(within(chosen));
  EXPECT_EQ(chosen.clocking.clk_hz, ice.default_clk_hz);
  EXPECT_TRUE(chosen.budget.ok());
  const auto sc9 = scale_scene(base, 9, 35000.0);
  const CoreClock serial_unit9 = choose_core_clock(ice, sc9, LoadPolicy::Stress, 0, 0, 1);
  EXPECT_LE(serial_unit9.core_min_hz, ice.default_clk_hz);
  EXPECT_FALSE(within(serial_unit9));
  const CoreClock chosen9 = choose_core_clock(ice, sc9, LoadPolicy::Stress);
  EXPECT_TRUE(chosen9.plan.spec.engine_fast_shift);
  EXPECT_TRUE(chosen9.plan.spec.neuron_unit);
  EXPECT_TRUE(within(chosen9));
  EXPECT_EQ(chosen9.clocking.clk_hz, ice.default_clk_hz);
  // --neurons engine stays: then the barrel shifter, the fastest left, at
  // the clock it needs.
  const CoreClock no_unit = choose_core_clock(ice, sc8, LoadPolicy::Stress, 0, -1, 0);
  EXPECT_TRUE(no_unit.plan.spec.engine_fast_shift);
  EXPECT_FALSE(no_unit.plan.spec.neuron_unit);
  EXPECT_EQ(no_unit.engine_clocks, barrel.engine_clocks);
  EXPECT_GE(no_unit.clocking.clk_hz, no_unit.core_min_hz);
  // A 12x12 skin: only barrel + unit keeps up at 18 MHz (serial + unit
  // needs more), so the board takes it at 18 MHz.
  const auto sc12 = scale_scene(base, 12, 35000.0);
  const CoreClock c12 = choose_core_clock(ice, sc12, LoadPolicy::Stress);
  EXPECT_TRUE(c12.plan.spec.engine_fast_shift);
  EXPECT_TRUE(c12.plan.spec.neuron_unit);
  EXPECT_LE(c12.core_min_hz, ice.default_clk_hz);
  EXPECT_EQ(c12.clocking.clk_hz, ice.default_clk_hz);
  EXPECT_GT(choose_core_clock(ice, sc12, LoadPolicy::Stress, 0, 0, 1).core_min_hz,
            ice.default_clk_hz);
  // A 16x16 skin: no engine keeps up at 18 MHz; the fastest is barrel +
  // unit, whose need is below every other engine's.
  const auto sc16 = scale_scene(base, 16, 35000.0);
  const CoreClock big = choose_core_clock(ice, sc16, LoadPolicy::Stress);
  EXPECT_TRUE(big.plan.spec.engine_fast_shift);
  EXPECT_TRUE(big.plan.spec.neuron_unit);
  EXPECT_GT(big.core_min_hz, ice.default_clk_hz);
  EXPECT_LT(big.core_min_hz, choose_core_clock(ice, sc16, LoadPolicy::Stress, 0, 0, 1).core_min_hz);
  // The clock asked for is the bar: a 6x6 skin's bit-serial engine needs
  // more than 18 MHz and keeps up with its measured load at 27, but not
  // with its bound (over 90 % of 27 000 clocks); the barrel shifter's
  // fits, so at 27 MHz the board takes the barrel shifter without the unit.
  const auto sc6 = scale_scene(base, 6, 35000.0);
  const CoreClock serial27 = choose_core_clock(ice, sc6, LoadPolicy::Stress, 27000000, 0, 0);
  EXPECT_TRUE(serial27.budget.ok());
  EXPECT_FALSE(within(serial27));
  const CoreClock at27 = choose_core_clock(ice, sc6, LoadPolicy::Stress, 27000000);
  EXPECT_TRUE(at27.plan.spec.engine_fast_shift);
  EXPECT_FALSE(at27.plan.spec.neuron_unit);
  EXPECT_TRUE(within(at27));
  EXPECT_LE(at27.core_min_hz, 27000000);
  EXPECT_TRUE(at27.budget.ok());
  // The default scene needs none of it.
  const CoreClock dflt = choose_core_clock(ice, base, LoadPolicy::Scene);
  EXPECT_FALSE(dflt.plan.spec.engine_fast_shift);
  EXPECT_FALSE(dflt.plan.spec.neuron_unit);
  std::printf("iCEBreaker 8x8: barrel %ld clocks (%.1f MHz), serial + unit %ld (%.1f MHz); "
              "12x12 barrel + unit %.1f MHz; 16x16 barrel + unit %.1f MHz; 6x6 barrel "
              "%.1f MHz\n",
              barrel.engine_clocks, barrel.core_min_hz / 1e6, serial_unit.engine_clocks,
              serial_unit.core_min_hz / 1e6, c12.core_min_hz / 1e6, big.core_min_hz / 1e6,
              at27.core_min_hz / 1e6);
}


}  // namespace

// At 1 MS/s the AD7476A's SCLK ties the ADC to a 37.3-40 MHz clock (or
// 74.7-80: SCLK = a / (2 H) <= 20 MHz with A - 28 H clocks of acquisition
// >= 250 ns). A 20x20 skin's engine fits the 40 MHz frame (about 23 400
// of 40 000 clocks with the neuron lanes): one clock. A 32x32 skin's
// (about 44 800) does not, and 75 MHz is beyond the ECP5 build's
// Fmax (about 50): the ULX3S gives the ADC a clock of its own from the
// same PLL (VCO / CLKOS_DIV, 40 MHz, the fastest that converts) and the
// core the slowest clock whose frame, floor(STEP clk A / a) - 1 clocks,
// holds the engine and whose sample period holds the DFT's lanes: 45 MHz
// (44 999 >= 44 792; 40 MHz's 39 999 does not). The iCE40 has no such
// clock; mixed_top (own_adc_clock false) neither. (The frame engine asked
// for: datapath 0; left to the board, the 32x32 takes the streaming one.)
TEST(CoreClock, AOneMegasampleSkinBeyondTheAdcBandGetsTheAdcItsOwnClock) {
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const Board ulx = find_board("ulx3s", "85k");
  const CoreClock s20 =
      choose_core_clock(ulx, scale_scene(base, 20, 1e6), LoadPolicy::Stress, 0, -1, -1, true, 0);
  ASSERT_TRUE(s20.budget.ok());
  EXPECT_EQ(s20.clocking.clk_hz, 40000000);
  EXPECT_EQ(s20.clocking.adc_clk_hz, 0);
  EXPECT_EQ(param(eskin::hls::dtmf_top_params(s20.plan, eskin::hls::dtmf_engine_image(s20.plan),
                                              "", ""),
                  "ADC_CLK_HZ"),
            "0");
  const CoreClock s32 =
      choose_core_clock(ulx, scale_scene(base, 32, 1e6), LoadPolicy::Stress, 0, -1, -1, true, 0);
  ASSERT_TRUE(s32.budget.ok()) << s32.budget.problems.front();
  EXPECT_GT(s32.engine_clocks, 40000);
  EXPECT_EQ(s32.clocking.clk_hz, 45000000);
  EXPECT_EQ(s32.clocking.adc_clk_hz, 40000000);
  EXPECT_EQ(s32.plan.spec.adc_clk_hz, 40000000);
  EXPECT_LT(s32.clocking.clk_hz, 74700000);
  EXPECT_GE(s32.budget.frame_clocks, s32.engine_clocks);
  EXPECT_EQ(s32.budget.adc_period, 40);
  EXPECT_EQ(s32.budget.frame_clocks, s32.clocking.clk_hz / 1000 - 1);
  EXPECT_EQ(s32.budget.period, s32.clocking.clk_hz / 1000000 - 1);
  const auto params =
      eskin::hls::dtmf_top_params(s32.plan, eskin::hls::dtmf_engine_image(s32.plan), "", "");
  EXPECT_EQ(param(params, "ADC_CLK_HZ"), "40000000");
  EXPECT_EQ(param(params, "CLK_HZ"), std::to_string(s32.clocking.clk_hz));
  // The PLL: VCO = clk x CLKOP_DIV = 40 MHz x CLKOS_DIV, in 400..800 MHz.
  auto wp = [&](const char* n) { return std::stol(param(s32.clocking.wrapper_params, n)); };
  const long vco = s32.clocking.clk_hz * wp("CLKOP_DIV");
  EXPECT_EQ(vco, 40000000L * wp("CLKOS_DIV"));
  EXPECT_GE(vco, 400000000L);
  EXPECT_LE(vco, 800000000L);
  EXPECT_EQ(s32.clocking.clk_hz, 25000000L * wp("CLKFB_DIV") / wp("CLKI_DIV"));
  // mixed_top's one clock: the 75 MHz band, or none.
  const CoreClock one = choose_core_clock(ulx, scale_scene(base, 32, 1e6), LoadPolicy::Stress, 0,
                                          -1, -1, false, 0);
  EXPECT_EQ(one.clocking.adc_clk_hz, 0);
  EXPECT_GE(one.clocking.clk_hz, 74700000);
  const CoreClock ice =
      choose_core_clock(find_board("icebreaker"), scale_scene(base, 4, 1e6), LoadPolicy::Stress);
  EXPECT_EQ(ice.clocking.adc_clk_hz, 0);
}

namespace {
// The scale table's scenes on the ECP5 with the board's choice of datapath,
// printed with the figures that chose it.
CoreClock board_choice(const Board& b, const eskin::sim::Scene& sc) {
  const CoreClock c = choose_core_clock(b, sc, LoadPolicy::Stress);
  std::printf("%s %s %dx%d at %g S/s: %s at %g MHz, %ld clocks measured (chain %llu), bound "
              "%llu (frame %llu + command %llu), frame %ld\n",
              b.name.c_str(), b.device.c_str(), c.plan.R, c.plan.C, c.plan.spec.sample_hz,
              datapath_name(c.plan.spec.datapath), c.clocking.clk_hz / 1e6, c.engine_clocks,
              (unsigned long long)c.load.chain_clocks, (unsigned long long)c.bound.total(),
              (unsigned long long)c.bound.frame, (unsigned long long)c.bound.command,
              c.budget.frame_clocks);
  return c;
}
}  // namespace

// The board's choice of datapath (choose_core_clock): the 64x64 skin at 1
// MS/s, which the frame engine cannot hold (47 817 DMEM words of its
// 32 768), gets the streaming datapath on the ECP5-85F, at a clock whose
// frame holds the control plane and the chain measured and 70 % of it the
// static bound; the default scene keeps the frame engine (both keep up at
// 30 MHz: the engine on a tie); asked for, each datapath is built.
TEST(CoreClock, TheBoardPicksTheStreamingDatapathWhereTheEngineDoesNotKeepUp) {
  const Board ulx = find_board("ulx3s", "85k");
  const auto sc64 = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/skin64x64.yaml");
  const CoreClock c = board_choice(ulx, sc64);
  ASSERT_EQ(c.plan.spec.datapath, eskin::hls::DtmfDatapath::Streaming);
  ASSERT_TRUE(c.budget.ok()) << c.budget.problems.front();
  EXPECT_FALSE(c.plan.spec.neuron_unit);
  EXPECT_EQ(c.plan.spec.neuron_lanes, 0);
  // The chain's own clocks: K + 45 + 2 (T - 1) + 3 with the dense packets
  // (the scene's outputs: amplitudes and taxels, no sparse, no spikes).
  EXPECT_EQ(c.load.chain_clocks, uint64_t(128 + 45 + 2 * 4095 + 3));
  EXPECT_EQ(c.bound.chain, c.load.chain_clocks);
  EXPECT_LE(uint64_t(c.engine_clocks), c.bound.total());
  EXPECT_LE(long(c.bound.total()) * 100, 70L * c.budget.frame_clocks);
  EXPECT_EQ(param(eskin::hls::dtmf_top_params(c.plan, eskin::hls::dtmf_engine_image(c.plan), "", ""),
                  "STREAM"),
            "1");
  // Asked for the engine, the skin is refused naming its memory.
  try {
    choose_core_clock(ulx, sc64, LoadPolicy::Stress, 0, -1, -1, true, 0);
    ADD_FAILURE() << "the frame engine was planned for a 64x64 skin";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("needs 47817 DMEM words"), std::string::npos) << e.what();
  }
  const auto base = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const CoreClock d = board_choice(ulx, base);
  EXPECT_EQ(d.plan.spec.datapath, eskin::hls::DtmfDatapath::FrameEngine);  // demixed carriers
  const auto planned = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/planned3x3.yaml");
  const CoreClock p = board_choice(ulx, planned);
  EXPECT_EQ(p.plan.spec.datapath, eskin::hls::DtmfDatapath::FrameEngine);
  EXPECT_EQ(p.clocking.clk_hz, ulx.default_clk_hz);
  const CoreClock ps = choose_core_clock(ulx, planned, LoadPolicy::Stress, 0, -1, -1, true, 1);
  EXPECT_EQ(ps.plan.spec.datapath, eskin::hls::DtmfDatapath::Streaming);
  EXPECT_TRUE(ps.budget.ok()) << ps.budget.problems.front();
  // Not with the neuron unit, and not on the UP5K.
  try {
    choose_core_clock(ulx, planned, LoadPolicy::Stress, 0, -1, 1, true, 1);
    ADD_FAILURE() << "the streaming datapath was planned with the neuron unit";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--neurons"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(find_board("icebreaker").streaming);
  for (int n : {16, 32})
    board_choice(ulx, scale_scene(base, n, 1e6));
}
