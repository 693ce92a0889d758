// The DFT lanes in the plan and the flow (pure planning, no tools run):
// common/eskin/dtmf_top_plan.h's budget at L lanes, dtmf_top_params' SDFT_LANES,
// and choose_sdft_lanes / choose_core_clock (host/fpga/flow.h) on both
// boards. The lanes' clocks themselves are asserted against the RTL by
// tests/rtl/sdft_lanes_test.cpp.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "ucode/dtmf_engine_image.h"
#include "eskin/dtmf_top_plan.h"
#include "host/fpga/board.h"
#include "host/fpga/flow.h"
#include "host/fpga/scale_table.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"

namespace {

using namespace eskin;

sim::Scene base() { return sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml"); }

std::string param(const std::vector<hls::VerilogParam>& ps, const std::string& name) {
  for (const auto& p : ps)
    if (p.name == name) return p.value;
  return "<missing>";
}

// dtmf_top's DFT clocks per sample (frame_capture takes a token every
// clock): 1 lane sdft_bank's 6 KS + 2; L >= 2 lanes 9 + (KS - 1) +
// (6 - L) (ceil(KS / L) - 1) up to 6 lanes, KS + 8 from 6 lanes on (the
// merger's token a clock; the next sample in the clock of the last token).
TEST(SdftLanesPlan, ClocksPerSampleAtEachLaneCount) {
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(8, 1), 50);
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(8, 2), 9 + 7 + 4 * 3);
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(9, 2), 9 + 8 + 4 * 4);
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(8, 3), 9 + 7 + 3 * 2);
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(24, 5), 9 + 23 + 1 * 4);
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(8, 6), 8 + 8);
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(8, 8), 8 + 8);
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(24, 6), 24 + 8);
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(32, 6), 40);  // 16x16 at 1 MS/s: 40 MHz
  EXPECT_EQ(hls::dtmf_top_sdft_clocks(24, 16), 24 + 8);
}

// Every sample but a frame's is skipped (no tokens): S = 6 ceil(KS / L) +
// 2. The ADC holds one sample, so the least period P the budget takes is
// max(S, floor(F / 2) + 1, ceil((F + (STEP - 1) S) / STEP)) (F the frame's
// sample, above: F < 2 P; STEP 1: every sample is a frame's, P = F).
// Figures at 1 MS/s (STEP 1000): 16x16 (32 channels) in 6 lanes 39; 24x24
// (48) in 8 lanes 39; 32x32 (64) in 11 lanes 39, in 10 lanes 45 (S = 44 >
// 40), in 16 lanes 37 (F = 72: at 36 = F / 2 the sample after a frame's is
// taken in the clock the next conversion lands, and that one is lost,
// tests/rtl/sdft_front_test.cpp NoFifoNeedsTheFrameSampleShorterThanTwoPeriods).
TEST(SdftLanesPlan, SkippedSamplesAndTheLeastPeriod) {
  EXPECT_EQ(hls::dtmf_top_sdft_skip_clocks(8, 1), 50);
  EXPECT_EQ(hls::dtmf_top_sdft_skip_clocks(8, 3), 6 * 3 + 2);
  EXPECT_EQ(hls::dtmf_top_sdft_skip_clocks(64, 11), 38);
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(8, 1, 35), 50);
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(24, 6, 1), 32);            // STEP 1: F
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(24, 6, 3), 28);            // (32 + 2 x 26) / 3
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(32, 6, 1000), 39);         // S 38, F 40
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(48, 8, 1000), 39);         // S 38, F 56
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(64, 11, 1000), 39);        // S 38, F 72
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(64, 10, 1000), 45);        // (72 + 999 x 44) / 1000
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(64, 16, 1000), 37);        // F 72: F < 2 P
  EXPECT_EQ(hls::dtmf_top_sdft_min_period(64, 16, 2), 49);           // (72 + 26) / 2
}

// The spec's lanes reach the Verilog parameters, the budget and its
// message; the plan refuses lanes beyond 16 or the channels.
TEST(SdftLanesPlan, LanesInTheParametersAndTheBudget) {
  auto spec = sim::dtmf_top_spec(fpga::scale_scene(base(), 4, 1e6));
  ASSERT_FALSE(spec.demix);  // 8 channels
  spec.sdft_lanes = 2;
  const auto plan = hls::make_dtmf_top_plan(spec);
  EXPECT_EQ(param(hls::dtmf_top_params(plan, hls::dtmf_engine_image(plan), "", ""), "SDFT_LANES"),
            "2");
  const auto at25 = hls::dtmf_top_clock_budget(plan, 25000000, 0);
  EXPECT_EQ(at25.sdft_clocks, 28);       // 9 + 7 + 4 x 3
  EXPECT_EQ(at25.sdft_skip_clocks, 26);  // 6 x 4 + 2
  EXPECT_EQ(at25.sdft_min_period, 27);   // (28 + 999 x 26) / 1000, rounded up
  bool named = false;
  for (const auto& p : at25.problems)
    named = named || p.find("sdft_lanes (2 lanes of KS = 8 channels): a frame's sample takes 28 "
                            "clocks, the others 26; with STEP 1000 that needs a sample period "
                            "of 27 clocks, the sample period is 25") != std::string::npos;
  EXPECT_TRUE(named) << "no DFT problem at 25 MHz";
  EXPECT_EQ(hls::dtmf_top_min_clock_hz(plan, 0), hls::dtmf_top_min_clock_hz_without_dft(plan, 0));
  for (int bad : {0, 9, 17}) {
    spec.sdft_lanes = bad;
    EXPECT_THROW(hls::make_dtmf_top_plan(spec), std::invalid_argument) << bad;
  }
  spec.sdft_lanes = 2;
  for (int bad : {-1, 3, 128}) {
    spec.sdft_fifo = bad;
    EXPECT_THROW(hls::make_dtmf_top_plan(spec), std::invalid_argument) << "FIFO " << bad;
  }
}

// scenes/skin64x64.yaml: 128 carriers on bin centres of a 512-sample window
// at 1 MS/s (no demixing: 128 DFT channels, the most frame_capture holds),
// one frame a millisecond (STEP 1000). A frame's sample takes F = 136
// clocks in any number of lanes from 6 on, every other one S = 6 ceil(128
// / L) + 2. The ADC on its own 40 MHz clock (the AD7476A's band), the core
// at clk: P = clk / 1 MHz - 1 (the CDC's clock of doubt).
hls::DtmfTopPlan sixty_four(int lanes, int fifo) {
  auto spec = sim::dtmf_top_spec(sim::load_scene(ESKIN_SOURCE_DIR "/scenes/skin64x64.yaml"));
  spec.sdft_lanes = lanes;
  spec.sdft_fifo = fifo;
  spec.adc_clk_hz = 40000000;
  spec.baud = 2000000;  // 20 clocks a bit at 40 MHz, 25 at 50
  return hls::make_dtmf_top_plan(spec);
}

std::string dft_problem(const hls::DtmfTopClockBudget& b) {
  for (const auto& p : b.problems)
    if (p.rfind("sdft_", 0) == 0) return p;
  return "";
}

TEST(SdftLanesPlan, SixtyFourBySixtyFourPlanHas128ChannelsAndA512SampleWindow) {
  const auto p = sixty_four(32, 4);
  EXPECT_EQ(p.K, 128);
  EXPECT_EQ(p.ks, 128);
  EXPECT_EQ(p.T, 4096);
  EXPECT_EQ(p.N, 512);
  EXPECT_EQ(p.step, 1000);
  EXPECT_FALSE(p.spec.demix);
  // With the demixing's DC channel a 64x64 skin would need 129: refused,
  // naming the reason.
  auto spec = p.spec;
  spec.demix = true;
  try {
    hls::make_dtmf_top_plan(spec);
    ADD_FAILURE() << "129 DFT channels accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected 1..128 DFT channels (carriers + the "
                                         "demixing's DC channel)"),
              std::string::npos) << e.what();
  }
}

// 32 lanes (S = 26) and a 4-sample FIFO keep up at 40 and 50 MHz (P = 39,
// 49; the FIFO holds floor(135 / P) = 3, 2 samples after a frame's); the
// least period is 27 (the catch-up: 1000 P >= 136 + 999 x 26), so 28 MHz
// (P = 27) passes and 27 MHz (P = 26) is refused for that reason.
TEST(SdftLanesPlan, SixtyFourBySixtyFourAtOneMegasampleIn32LanesWithAFourSampleFifo) {
  const auto p = sixty_four(32, 4);
  for (long clk : {40000000L, 50000000L}) {
    const auto b = hls::dtmf_top_clock_budget(p, clk, 0);
    EXPECT_TRUE(b.ok()) << clk << ": " << b.problems.front();
    EXPECT_EQ(b.sdft_clocks, 136);
    EXPECT_EQ(b.sdft_skip_clocks, 26);
    EXPECT_EQ(b.sdft_min_period, 27);
    EXPECT_EQ(b.period, clk / 1000000 - 1);
    EXPECT_EQ(b.sdft_backlog, clk == 40000000L ? 3 : 2);
  }
  EXPECT_EQ(dft_problem(hls::dtmf_top_clock_budget(p, 28000000, 0)), "");
  const std::string why = dft_problem(hls::dtmf_top_clock_budget(p, 27000000, 0));
  EXPECT_NE(why.find("sdft_lanes (32 lanes of KS = 128 channels, a 4-sample FIFO): a frame's "
                     "sample takes 136 clocks, the others 26; with STEP 1000 that needs a sample "
                     "period of 27 clocks, the sample period is 26 (27 MHz / 1e+06 S/s): the "
                     "samples queued after a frame's (the next 110 clocks late) do not catch up"),
            std::string::npos) << why;
}

// At 40 MHz (P = 39) each of the three conditions at its edge: the FIFO
// (F < (D + 2) P: 2 samples are the fewest, 1 is refused, and none, the
// ADC's register alone as rtl/dtmf_top.v is wired today), and the lanes (S
// <= P: 22 lanes, S = 38, are the fewest; 21 take 44 and need 45).
TEST(SdftLanesPlan, SixtyFourBySixtyFourAt40MHzRefusesTooSmallAFifoOrTooFewLanes) {
  EXPECT_EQ(dft_problem(hls::dtmf_top_clock_budget(sixty_four(32, 2), 40000000, 0)), "");
  for (int fifo : {0, 1}) {
    const std::string why =
        dft_problem(hls::dtmf_top_clock_budget(sixty_four(32, fifo), 40000000, 0));
    EXPECT_NE(why.find("the 3 samples converted while a frame's sample holds the lanes do not "
                       "fit " + std::string(fifo ? "the 1-sample FIFO and " : "") +
                       "the ADC's one register (F < (" + std::to_string(fifo) + " + 2) P)"),
              std::string::npos) << why;
  }
  EXPECT_EQ(dft_problem(hls::dtmf_top_clock_budget(sixty_four(22, 4), 40000000, 0)), "");
  const std::string why = dft_problem(hls::dtmf_top_clock_budget(sixty_four(21, 4), 40000000, 0));
  EXPECT_NE(why.find("the others 44; with STEP 1000 that needs a sample period of 45 clocks, the "
                     "sample period is 39 (40 MHz / 1e+06 S/s): the skipped samples take longer "
                     "than a sample period"),
            std::string::npos) << why;
}

// A 4x4 skin at 1 MS/s on the ULX3S: one lane would need 50 MHz, outside
// the AD7476A's band at SCLK_DIV 1 (37.3..40 MHz, docs/bitstream.md); two
// lanes need 28, below the ADC's 37.3, and are the fewest that do. The
// clock is then in that band, and every budget holds there.
TEST(SdftLanesPlan, FourByFourAtOneMegasampleTakesLanesOnTheUlx3s) {
  const auto sc = fpga::scale_scene(base(), 4, 1e6);
  const fpga::Board b = fpga::find_board("ulx3s", "85k");
  const auto c = fpga::choose_core_clock(b, sc, fpga::LoadPolicy::Stress);
  const int lanes = c.plan.spec.sdft_lanes;
  EXPECT_GT(lanes, 1);
  EXPECT_LE(lanes, b.max_sdft_lanes);
  const long other = hls::dtmf_top_min_clock_hz_without_dft(c.plan, c.engine_clocks);
  const long step = c.plan.step;
  EXPECT_LE(hls::dtmf_top_sdft_min_period(c.plan.ks, lanes, step), c.budget.period);
  EXPECT_GT(hls::dtmf_top_sdft_min_period(c.plan.ks, lanes - 1, step), c.budget.period)
      << "fewer lanes would do";
  EXPECT_EQ(c.core_min_hz, other) << "the DFT sets the minimum clock";
  const std::string why = hls::dtmf_top_min_clock_reason(c.plan, c.engine_clocks);
  EXPECT_EQ(why.rfind("the AD7476A's acquisition time 37.3 MHz, ", 0), 0u) << why;
  EXPECT_NE(why.find(" clocks a sample in " + std::to_string(lanes) + " lanes "),
            std::string::npos) << why;
  ASSERT_TRUE(c.budget.ok()) << c.budget.problems.front();
  EXPECT_LE(c.clocking.clk_hz, 40000000);
  EXPECT_EQ(c.plan.spec.clk_hz, c.clocking.clk_hz);
}

// A 12x12 skin at 1 MS/s on the ULX3S (24 carriers, no DC): 3 lanes, the
// most while frame_capture took a token every 2 clocks, needed 56 clocks a
// sample, beyond the ADC's first band (37.3..40 MHz); with a token a clock
// and skipped samples more lanes help, and the flow's fewest that need no
// faster clock than the ADC and the engine are more than 3 and at most 6
// (6 lanes: S = 26, F = 32, least period 27). The clock is then in the
// first band, and every budget holds there.
TEST(SdftLanesPlan, TwelveByTwelveAtOneMegasampleTakesMoreThanThreeLanesOnTheUlx3s) {
  const auto sc = fpga::scale_scene(base(), 12, 1e6);
  const fpga::Board b = fpga::find_board("ulx3s", "85k");
  const auto c = fpga::choose_core_clock(b, sc, fpga::LoadPolicy::Stress);
  ASSERT_EQ(c.plan.ks, 24);
  EXPECT_GT(hls::sdft_lanes_interval(24, 3, 2), 40);  // the old capture's pace
  const int lanes = c.plan.spec.sdft_lanes;
  EXPECT_GT(lanes, 3);
  EXPECT_LE(lanes, b.max_sdft_lanes);
  EXPECT_LE(lanes, 6);
  ASSERT_TRUE(c.budget.ok()) << c.budget.problems.front();
  EXPECT_LE(c.budget.sdft_min_period, c.budget.period);
  EXPECT_LE(c.clocking.clk_hz, 40000000);
}

// A 32x32 skin at 1 MS/s (64 carriers) on the ULX3S: the DFT alone (an
// engine that needs nothing) gets lanes that keep up with the ADC at a
// clock in its first band, so the DFT is no longer what stops this row
// (tests/rtl/dft_capture_test.cpp runs 11 lanes at 40 clocks a sample).
TEST(SdftLanesPlan, ThirtyTwoByThirtyTwoAtOneMegasampleDftKeepsUpOnTheUlx3s) {
  const fpga::Board b = fpga::find_board("ulx3s", "85k");
  auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(fpga::scale_scene(base(), 32, 1e6)));
  ASSERT_EQ(plan.ks, 64);
  plan.spec.sdft_lanes = fpga::choose_sdft_lanes(b, plan, 0);
  EXPECT_GE(plan.spec.sdft_lanes, 11);
  EXPECT_LE(plan.spec.sdft_lanes, 16);
  const long min_hz = hls::dtmf_top_min_clock_hz(plan, 0);
  EXPECT_LE(min_hz, 40000000);
  plan.spec.baud = 2000000;  // 40 MHz's exact rate (host/fpga/board.cpp)
  const auto at40 = hls::dtmf_top_clock_budget(plan, 40000000, 0);
  EXPECT_TRUE(at40.ok()) << at40.problems.front();
}

// scenes/skin64x64.yaml on the ULX3S, the DFT alone (an engine that needs
// nothing; the ADC's band sets the clock, 37.3..40 MHz, P = 39 with the
// ADC on a clock of its own): no number of lanes keeps up without a FIFO
// (a frame's sample holds the lanes F = 136 >= 2 P clocks), so the flow
// counts the 4-sample FIFO: the fewest lanes with S = 6 ceil(128 / L) + 2
// <= 39 are 22 (S = 38; 21 lanes: 44), and the FIFO it then gives is 4.
TEST(SdftLanesPlan, SixtyFourBySixtyFourTakesLanesAndTheFifoOnTheUlx3s) {
  const fpga::Board b = fpga::find_board("ulx3s", "85k");
  auto plan = hls::make_dtmf_top_plan(
      sim::dtmf_top_spec(sim::load_scene(ESKIN_SOURCE_DIR "/scenes/skin64x64.yaml")));
  ASSERT_EQ(plan.ks, 128);
  for (int lanes : {6, 22, 64})
    EXPECT_GT(hls::dtmf_top_sdft_min_period(128, lanes, plan.step, 0), 40) << lanes << " lanes";
  plan.spec.sdft_lanes = fpga::choose_sdft_lanes(b, plan, 0);
  EXPECT_EQ(plan.spec.sdft_lanes, 22);
  EXPECT_EQ(hls::dtmf_top_sdft_skip_clocks(128, 22), 38);
  EXPECT_EQ(hls::dtmf_top_sdft_skip_clocks(128, 21), 44);
  EXPECT_EQ(fpga::choose_sdft_fifo(b, plan, 0), 4);
  plan.spec.sdft_fifo = 4;
  EXPECT_EQ(dft_problem(hls::dtmf_top_clock_budget(plan, 40000000, 0)), "");
  plan.spec.sdft_fifo = 0;
  EXPECT_NE(dft_problem(hls::dtmf_top_clock_budget(plan, 40000000, 0)), "");
  // A plan that keeps up without one keeps none (the 32x32's 11 lanes).
  auto p32 = hls::make_dtmf_top_plan(sim::dtmf_top_spec(fpga::scale_scene(base(), 32, 1e6)));
  p32.spec.sdft_lanes = fpga::choose_sdft_lanes(b, p32, 0);
  EXPECT_EQ(fpga::choose_sdft_fifo(b, p32, 0), 0);
}

// The iCEBreaker never gets a second lane, whatever the skin asks.
TEST(SdftLanesPlan, IcebreakerKeepsOneLane) {
  const fpga::Board b = fpga::find_board("icebreaker");
  EXPECT_EQ(b.max_sdft_lanes, 1);
  for (int n : {2, 4, 6}) {
    const auto spec = sim::dtmf_top_spec(fpga::scale_scene(base(), n, 1e6));
    const auto plan = hls::make_dtmf_top_plan(spec);
    EXPECT_EQ(fpga::choose_sdft_lanes(b, plan, 0), 1) << n << "x" << n;
    EXPECT_EQ(fpga::choose_sdft_fifo(b, plan, 0), 0) << n << "x" << n;  // nor a FIFO
  }
  const auto c = fpga::choose_core_clock(b, fpga::scale_scene(base(), 4, 1e6),
                                         fpga::LoadPolicy::Stress);
  EXPECT_EQ(c.plan.spec.sdft_lanes, 1);
  EXPECT_EQ(c.core_min_hz, 50000000);  // the DFT's 6 KS + 2 = 50 clocks per sample set it
  const std::string why = hls::dtmf_top_min_clock_reason(c.plan, c.engine_clocks);
  EXPECT_NE(why.find("the DFT's 50 clocks a sample in 1 lane 50.0 MHz"), std::string::npos) << why;
}

// The default scene at 35 kS/s needs no lanes on either board.
TEST(SdftLanesPlan, DefaultSceneNeedsOneLane) {
  for (const char* name : {"icebreaker", "ulx3s"}) {
    const auto c = fpga::choose_core_clock(fpga::find_board(name), base(), fpga::LoadPolicy::Scene);
    EXPECT_EQ(c.plan.spec.sdft_lanes, 1) << name;
  }
}

}  // namespace
