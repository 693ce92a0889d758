// The static frame bound (ucode/dtmf_frame_bound.h) against the measured
// engine load (host/fpga/engine_load.h), and the plan's refusal of a build
// whose bound exceeds its share of the frame (common/eskin/dtmf_top_plan.h,
// host/fpga/flow.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "eskin/dtmf_top_plan.h"
#include "host/fpga/board.h"
#include "host/fpga/engine_load.h"
#include "host/fpga/flow.h"
#include "host/fpga/scale_table.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "ucode/dtmf_frame_bound.h"

namespace {

using namespace eskin;

sim::Scene base() { return sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml"); }

// The measured worst case (stress frames with a frame's most packets on the
// longest, and the longest command) is below the proven bound, part by part,
// and the bound is not far above it. Plans: the default scene (3x3, the
// engine's neurons, bit-serial), the scale table's UP5K 8x8 (bit-serial,
// neuron unit), the staggered 10x10 scene (barrel shifter, neuron unit) and
// an ECP5 16x16 with the neuron lanes and the barrel shifter.
//
// How loose: the bound adds up what no one frame does together (a spike in
// every neuron of both layers, every packet type, the sparse one over
// every taxel twice, the site rule and the pairing at their longest), and
// the polling of the DFT for its longest busy time (the measurement's DFT
// takes carrier writes at once). Observed (printed): total bound / measured
// 1.2 to 1.9. The bound must stay within 2.5x of the measurement: looser
// than that it would refuse builds that keep up by a wide margin.
TEST(FrameBound, MeasuredWorstCaseIsBelowTheBound) {
  struct Case {
    std::string name;
    hls::DtmfTopPlan plan;
  };
  std::vector<Case> cases;
  const sim::Scene b = base();
  cases.push_back({"default 3x3", hls::make_dtmf_top_plan(sim::dtmf_top_spec(b, hls::kDtmfTopClkHz))});
  {
    auto spec = sim::dtmf_top_spec(fpga::scale_scene(b, 8, 35000.0));
    spec.neuron_unit = true;
    cases.push_back({"UP5K 8x8, serial + unit", hls::make_dtmf_top_plan(spec)});
  }
  {
    auto spec = sim::dtmf_top_spec(sim::load_scene(ESKIN_SOURCE_DIR "/scenes/staggered10x10.yaml"));
    spec.engine_fast_shift = true;
    spec.neuron_unit = true;
    cases.push_back({"staggered 10x10, barrel + unit", hls::make_dtmf_top_plan(spec)});
  }
  {
    auto spec = sim::dtmf_top_spec(fpga::scale_scene(b, 16, 35000.0));
    spec.engine_fast_shift = true;
    spec.neuron_unit = true;
    spec.neuron_lanes = 5;
    cases.push_back({"ECP5 16x16, barrel + lanes", hls::make_dtmf_top_plan(spec)});
  }
  for (const auto& c : cases) {
    const fpga::EngineLoad load = fpga::measure_engine_load(c.plan, {});
    const hls::DtmfFrameBound bound = hls::dtmf_frame_bound(c.plan);
    const double ratio = double(bound.total()) / double(load.stress_total());
    std::printf("%-32s measured frame %6llu command %5llu total %6llu | bound frame %6llu command "
                "%5llu total %6llu (x%.2f) | any %6llu + %5llu\n",
                c.name.c_str(), (unsigned long long)load.stress_bound(),
                (unsigned long long)load.command_clocks, (unsigned long long)load.stress_total(),
                (unsigned long long)bound.frame, (unsigned long long)bound.command,
                (unsigned long long)bound.total(), ratio, (unsigned long long)bound.frame_any,
                (unsigned long long)bound.command_any);
    EXPECT_LE(load.stress_bound(), bound.frame) << c.name;
    EXPECT_LE(load.command_clocks, bound.command) << c.name << ": " << load.command_case;
    EXPECT_LE(load.stress_total(), bound.total()) << c.name;
    EXPECT_LT(ratio, 2.5) << c.name;
    // Without the plan's assumptions the bound can only grow.
    EXPECT_GE(bound.frame_any, bound.frame) << c.name;
    EXPECT_GE(bound.command_any, bound.command) << c.name;
  }
}

// The budget refuses a bound beyond 90 % of the frame on the frame engine
// (70 % on a streaming datapath), naming the bound, its share, the frame and
// the limit. The default plan at 18 MHz: 35 x 514 = 17 990 clocks a frame,
// 90 %: 16 191, 70 %: 12 593.
TEST(FrameBound, BudgetRefusesABoundBeyondTheLimit) {
  const auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(base(), hls::kDtmfTopClkHz));
  const auto ok = hls::dtmf_top_clock_budget(plan, 18000000, 12000, 16191);
  EXPECT_TRUE(ok.ok()) << (ok.problems.empty() ? "" : ok.problems[0]);
  EXPECT_EQ(ok.frame_clocks, 17990);
  EXPECT_EQ(ok.bound_limit_clocks, 16191);
  const auto over = hls::dtmf_top_clock_budget(plan, 18000000, 12000, 16192);
  ASSERT_EQ(over.problems.size(), 1u);
  EXPECT_EQ(over.problems[0],
            "frame_engine: the static bound of a frame and a command, 16192 clocks, is 90.0 % of "
            "a frame of 17990 clocks; a build may take at most 90 % (16191 clocks) "
            "(18 MHz / 35000 S/s)");
  auto streaming = plan;
  streaming.spec.datapath = hls::DtmfDatapath::Streaming;
  const auto s = hls::dtmf_top_clock_budget(streaming, 18000000, 12000, 12594);
  EXPECT_EQ(s.bound_limit_clocks, 12593);
  ASSERT_EQ(s.problems.size(), 1u);
  EXPECT_NE(s.problems[0].find("at most 70 % (12593 clocks)"), std::string::npos) << s.problems[0];
  EXPECT_TRUE(hls::dtmf_top_clock_budget(streaming, 18000000, 12000, 12593).ok());
}

// The flow keeps the bound within the limit at the clock it picks: the
// default scene on the iCEBreaker keeps up at 18 MHz with its bound under
// 90 % of the frame, and the report carries the bound.
TEST(FrameBound, FlowChecksTheBoundAtTheChosenClock) {
  const fpga::CoreClock c = fpga::choose_core_clock(fpga::find_board("icebreaker"), base(),
                                                    fpga::LoadPolicy::Stress);
  std::printf("icebreaker default: %ld Hz, frame %ld clocks, bound %llu (limit %ld)\n",
              c.clocking.clk_hz, c.budget.frame_clocks, (unsigned long long)c.bound.total(),
              c.budget.bound_limit_clocks);
  EXPECT_TRUE(c.budget.ok());
  EXPECT_EQ(c.budget.bound_clocks, long(c.bound.total()));
  EXPECT_LE(c.budget.bound_clocks, c.budget.bound_limit_clocks);
  EXPECT_EQ(c.bound.total(), hls::dtmf_frame_bound(c.plan).total());
}

}  // namespace

namespace {

// The scale table's 32x32 ECP5 builds (docs/scale_table.csv: 50 MHz, the
// barrel shifter and the neuron lanes; at 1 MS/s the ADC on its own 40 MHz
// clock) measured 49 778 of 50 015 clocks a frame: their static bound is
// beyond 90 % of it, so the plan refuses them at 50 MHz, naming the bound,
// the frame and the limit; the slowest clock that would hold the bound is
// above the 50 MHz those builds reached (their Fmax: about 50.5).
TEST(FrameBound, ScaleTable32x32OnTheEcp5IsRefusedAt50MHz) {
  const auto ulx = fpga::find_board("ulx3s", "85k");
  for (double fs : {35000.0, 1e6}) {
    const fpga::CoreClock c = fpga::choose_core_clock(ulx, fpga::scale_scene(base(), 32, fs),
                                                      fpga::LoadPolicy::Stress, 50000000);
    std::printf("32x32 at %g S/s, 50 MHz: measured %ld, bound %llu (frame %llu + command %llu) of "
                "a frame of %ld (limit %ld); needs %ld Hz\n",
                fs, c.engine_clocks, (unsigned long long)c.bound.total(),
                (unsigned long long)c.bound.frame, (unsigned long long)c.bound.command,
                c.budget.frame_clocks, c.budget.bound_limit_clocks, c.core_min_hz);
    EXPECT_FALSE(c.budget.ok());
    bool named = false;
    for (const auto& p : c.budget.problems)
      named |= p.find("frame_engine: the static bound of a frame and a command, " +
                      std::to_string(c.bound.total()) + " clocks") != std::string::npos &&
               p.find("a build may take at most 90 %") != std::string::npos;
    EXPECT_TRUE(named);
    EXPECT_LE(c.engine_clocks, c.budget.frame_clocks);  // the measurement alone kept up
    EXPECT_GT(c.core_min_hz, 51000000);
  }
}

}  // namespace
