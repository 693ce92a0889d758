// host/fpga/engine_load.h: the frame engine's measured clocks per frame and
// command, and the clock budget of common/eskin/dtmf_top_plan.h built on them.
#include <gtest/gtest.h>

#include <algorithm>

#include <cstdio>
#include <set>
#include <string>

#include "hls/dtmf_chain.h"
#include "eskin/dtmf_top_plan.h"
#include "host/fpga/board.h"
#include "host/fpga/engine_load.h"
#include "host/fpga/flow.h"
#include "host/fpga/scale_table.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"
#include "tests/ucode/dtmf_top_model.h"

namespace {

using namespace eskin;

void print(const fpga::EngineLoad& l) {
  for (const auto& [name, clocks] : l.cases)
    std::printf("  %-28s %8llu clocks\n", name.c_str(), (unsigned long long)clocks);
}

// The scene figure must be the longest frame of the clocked top model of
// tests/hls (sdft_bank's HLS model, the same microcode on the same ISS,
// checked packet for packet against the HLS chain by
// tests/ucode/dtmf_ucode_test.cpp) on the same samples: engine_load builds
// the frames from its own exact window sums, so any difference in the
// frames or their timing shows. The stress figure drives the same paths
// harder, so it must be at least the scene's, and (the same program) within
// 2x of it. The scene has the ghost filter, so each of the 5 signals runs
// twice, the second time with every taxel a site: that runs the product
// and the site rule for every taxel and drives every neuron (on this skin
// within a few clocks of the longest frame, which either run may give).
TEST(EngineLoad, SceneFigureIsTheTopModelsAndStressBoundsIt) {
  const sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(sc, hls::kDtmfTopClkHz));
  sim::WorldModel world(sc);
  const auto codes = world.all_codes();
  const int up = 12 - sc.skin.adc.bits;
  std::vector<int32_t> x;
  for (int c : codes) x.push_back((c << up) - 2048);
  const fpga::EngineLoad load = fpga::measure_engine_load(plan, x);
  print(load);
  const long period = std::lround(double(hls::kDtmfTopClkHz) / sc.skin.adc.rate_hz);
  dtmf_model::TopModel<hls::DtmfChainSizes<3, 3, 32>> top(plan, period);
  for (int c : codes) top.sample(uint16_t(c << up));
  std::printf("default scene: %d frames, longest %llu clocks (top model %llu); stress %llu (%s), "
              "command %llu (%s)\n",
              load.scene_frames, (unsigned long long)load.scene_clocks,
              (unsigned long long)top.max_frame_clocks(), (unsigned long long)load.stress_clocks,
              load.stress_case.c_str(), (unsigned long long)load.command_clocks,
              load.command_case.c_str());
  EXPECT_EQ(load.scene_frames, int((codes.size() - 32) / 35 + 1));
  EXPECT_EQ(load.scene_clocks, top.max_frame_clocks());
  EXPECT_GE(load.stress_clocks, load.scene_clocks);
  EXPECT_LE(load.stress_clocks, 2 * load.scene_clocks);
  EXPECT_GT(load.command_clocks, 0u);
  EXPECT_EQ(load.stress_frames, 2 * 5 * 64);
  EXPECT_EQ(std::count_if(load.cases.begin(), load.cases.end(),
                          [](const auto& c) {
                            return c.first.find(", every taxel a site") != std::string::npos;
                          }),
            5);
}

// The budget at a clock: the default plan at 18 MHz has 514 clocks per
// sample (round(18e6 / 35e3)), SCLK_DIV 1, STEP 35: 17 990 clocks a frame;
// 6 KS + 2 = 44 for the DFT (7 channels with demixing). At 12 MHz the frame
// has 35 x 343 = 12 005 clocks, fewer than the engine needs.
TEST(ClockBudget, DefaultPlanAt18And12MHz) {
  const sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(sc, hls::kDtmfTopClkHz));
  const auto b18 = hls::dtmf_top_clock_budget(plan, 18000000, 16900);
  EXPECT_EQ(b18.period, 514);
  EXPECT_EQ(b18.sclk_div, 1);
  EXPECT_EQ(b18.sdft_clocks, 44);
  EXPECT_EQ(b18.frame_clocks, 17990);
  EXPECT_TRUE(b18.ok()) << b18.problems.front();
  const auto b12 = hls::dtmf_top_clock_budget(plan, 12000000, 16900);
  EXPECT_EQ(b12.frame_clocks, 12005);
  ASSERT_EQ(b12.problems.size(), 1u);
  EXPECT_NE(b12.problems[0].find("frame_engine: its longest frame and command take 16900 clocks, "
                                 "a frame is STEP x period = 35 x 343 = 12005"),
            std::string::npos)
      << b12.problems[0];
  // 16900 clocks at 35 kS/s / 35 samples per frame: 16.9 MHz at least.
  EXPECT_EQ(hls::dtmf_top_min_clock_hz(plan, 16900), 16900000);
}

// At 1 MS/s (a 3x3 skin on bin centres: 6 channels, 38 DFT clocks) the
// AD7476A leaves a narrow band: the acquisition time (period - 28 H clocks
// >= 250 ns) needs clk >= 28 / 750 ns = 37.3 MHz with H = 1, the DFT
// 38 MHz, and H = ceil(clk / 40 MHz) doubles above 40 MHz, which leaves
// (42 - 56) clocks: nothing.
TEST(ClockBudget, OneMegasampleBandOfTheAdc) {
  const auto base = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(fpga::scale_scene(base, 3, 1e6)));
  plan.spec.baud = 2000000;  // 20 clocks per bit at 40 MHz (3 Mbaud would be 2.6 % off)
  ASSERT_FALSE(plan.spec.demix);
  ASSERT_EQ(plan.ks, 6);
  EXPECT_TRUE(hls::dtmf_top_clock_budget(plan, 40000000, 0).ok());
  const auto at36 = hls::dtmf_top_clock_budget(plan, 36000000, 0);
  ASSERT_EQ(at36.problems.size(), 2u);
  EXPECT_NE(at36.problems[0].find("adc_ad7476: a sample period of 36 clocks leaves 222 ns"),
            std::string::npos) << at36.problems[0];
  EXPECT_NE(at36.problems[1].find("sdft_bank: needs 6 KS + 2 = 38 clocks per sample, the sample "
                                  "period is 36"),
            std::string::npos) << at36.problems[1];
  const auto at42 = hls::dtmf_top_clock_budget(plan, 42000000, 0);
  ASSERT_EQ(at42.problems.size(), 1u);
  EXPECT_NE(at42.problems[0].find("at SCLK_DIV 2"), std::string::npos) << at42.problems[0];
  EXPECT_EQ(hls::dtmf_top_min_clock_hz(plan, 0), 38000000);
  // 2 MS/s: 500 ns per sample minus 250 ns of acquisition is less than the
  // 28 SCLK half periods (>= 700 ns at 20 MHz) of a conversion.
  auto fast = plan;
  fast.spec.sample_hz = 2e6;
  EXPECT_EQ(hls::dtmf_top_min_clock_hz(fast, 0), 0);
  // 3 Mbaud at 40 MHz: 13 clocks per bit, 2.6 % fast.
  plan.spec.baud = 3000000;
  const auto uart = hls::dtmf_top_clock_budget(plan, 40000000, 0);
  ASSERT_EQ(uart.problems.size(), 1u);
  EXPECT_NE(uart.problems[0].find("uart: 3000000 baud is 13 clocks per bit at 40 MHz (2.6 % off)"),
            std::string::npos) << uart.problems[0];
}

// A skin whose engine image is beyond the frame engine's address space
// (DMEM 2^15 words) is refused with the numbers, before any tool runs:
// 56x56 has 3136 taxels, and the DMEM holds 12 words per taxel (pending,
// site, g, 6 of neuron state, 2 spike flags, layer 2 input) = 37 632.
TEST(EngineLoad, RefusesASkinBeyondTheEnginesMemory) {
  const auto base = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(fpga::scale_scene(base, 56, 35000)));
  try {
    fpga::measure_engine_load(plan, {});
    FAIL() << "56x56 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("a 56x56 skin needs"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at most 32768"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

// The longest stress frame by routine: every clock of it in exactly one
// routine of the program, so the routines add up to the frame: the frame
// ends at the FRAME_DONE write, in the first of the `out`'s two clocks, the
// profile at the end of that instruction, one clock later. Every name is a
// section of rtl/ucode/dtmf_chain.fe. On a 6x6 skin (72 neurons, two
// layers) the neurons' update is the largest share, as the instruction
// counts say (about 80 instructions per neuron, ~20 per taxel elsewhere).
TEST(EngineLoad, LongestStressFrameByRoutine) {
  const auto base = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(fpga::scale_scene(base, 6, 35000.0)));
  const fpga::EngineLoad load = fpga::measure_engine_load(plan, {});
  uint64_t sum = 0;
  const std::set<std::string> sections = {"boot", "main", "carrier_demix", "carrier_magnitude",
                                          "taxel_reconstruct", "ghost_filter", "neurons",
                                          "izhikevich_layer", "synapse_weights", "spike_window",
                                          "spike_encoder", "packets", "status", "commands"};
  for (const auto& [name, clocks] : load.stress_routines) {
    std::printf("  %-20s %7llu clocks\n", name.c_str(), (unsigned long long)clocks);
    EXPECT_TRUE(sections.count(name)) << name;
    sum += clocks;
  }
  EXPECT_EQ(sum, load.stress_clocks + 1);
  ASSERT_FALSE(load.stress_routines.empty());
  EXPECT_EQ(load.stress_routines.front().first, "izhikevich_layer");
}

}  // namespace

namespace {

// Packets fall on the frames the decimation counters pick, so the stress
// signals' own alignment can miss the worst case: the 18x18 skin at 1 MS/s
// as the ULX3S flow plans it (2 Mbaud, packets every 6th frame) had its
// longest frame (38 055 clocks, all carriers toggling) on a frame without
// its largest packets. The bound puts a frame's most packets on the
// longest frame without them. Checks: the bound is above the longest
// frame here (the gap it closes) and is what the budget uses (plus the
// longest command); the most packets of a frame are at least a full spike
// window's: its MAX_SPIKES events of 5 bytes, one `out` (a clock at
// least) a byte, so the stress signals fill a window.
TEST(EngineLoad, StressBoundPutsAFramesMostPacketsOnTheLongestFrame) {
  const auto base = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const fpga::CoreClock c = fpga::choose_core_clock(
      fpga::find_board("ulx3s", "85k"), fpga::scale_scene(base, 18, 1e6), fpga::LoadPolicy::Stress);
  const fpga::EngineLoad& load = c.load;
  std::printf("18x18, 1 MS/s: longest frame %llu; without its packets %llu + most packets %llu = %llu\n",
              (unsigned long long)load.stress_clocks, (unsigned long long)load.stress_other_clocks,
              (unsigned long long)load.stress_packet_clocks, (unsigned long long)load.stress_bound());
  EXPECT_GT(load.stress_bound(), load.stress_clocks);
  EXPECT_EQ(load.stress_bound(), load.stress_other_clocks + load.stress_packet_clocks);
  EXPECT_EQ(c.engine_clocks, long(load.stress_bound() + load.command_clocks));
  EXPECT_GE(load.stress_packet_clocks, 5u * uint64_t(c.plan.max_spikes));
  EXPECT_LT(load.stress_other_clocks, load.stress_clocks);  // the longest frame held some, not the most
}

}  // namespace
