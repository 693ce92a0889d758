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
// an ECP5 16x16 with the neuron lanes and the barrel shifter; and on the
// streaming datapath the 64x64 skin at 1 MS/s and the planned 3x3 with
// spikes (the chain's fixed clocks in both figures).
//
// How loose: the bound adds up what no one frame does together (a spike in
// every neuron of both layers, every packet type, the sparse one over
// every taxel twice when the mask asks, the site rule and the pairing at
// their longest), and the DFT's polls for the samples it may be on during
// a carrier load (the measurement's DFT
// takes carrier writes at once). Observed (printed): total bound / measured
// 1.20 (3x3), 1.53 (8x8), 1.76 (10x10), 1.46 (16x16), 1.21 (64x64
// streaming), 1.98 (3x3 streaming with spikes: the spike tail's events for
// every neuron of both layers and a full SPIKES packet, which no stress
// frame of the model reaches, in both figures alike). The bound must stay within 2x of the measurement: looser than
// that it would refuse builds that keep up with half their frame to spare.
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
  {  // the streaming datapath: the control plane's measured and proven
     // frames, the chain's fixed clocks added to both
    auto spec = sim::dtmf_top_spec(sim::load_scene(ESKIN_SOURCE_DIR "/scenes/skin64x64.yaml"),
                                   40000000);
    spec.datapath = hls::DtmfDatapath::Streaming;
    spec.engine_fast_shift = true;
    spec.neuron_unit = false;
    spec.sdft_lanes = 22;
    spec.sdft_fifo = 4;
    cases.push_back({"ECP5 64x64 1 MS/s, streaming", hls::make_dtmf_top_plan(spec)});
    auto p3 = sim::dtmf_top_spec(sim::load_scene(ESKIN_SOURCE_DIR "/scenes/planned3x3.yaml"),
                                 hls::kDtmfTopClkHz);
    p3.datapath = hls::DtmfDatapath::Streaming;
    p3.spikes = true;
    cases.push_back({"planned 3x3, streaming, spikes", hls::make_dtmf_top_plan(p3)});
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
    EXPECT_LT(ratio, 2.0) << c.name;
    // Without the plan's assumptions the bound can only grow.
    EXPECT_GE(bound.frame_any, bound.frame) << c.name;
    EXPECT_GE(bound.command_any, bound.command) << c.name;
    const bool stream = c.plan.spec.datapath == hls::DtmfDatapath::Streaming;
    EXPECT_EQ(load.chain_clocks, stream ? bound.chain : 0u) << c.name;
    EXPECT_EQ(bound.chain, stream ? uint64_t(hls::dtmf_chain_frame_clocks(c.plan, c.plan.mask)) : 0u)
        << c.name;
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
  EXPECT_EQ(s.problems[0].rfind("streaming datapath: the static bound of a frame and a command, "
                                "12594 clocks, is 70.0 % of a frame of 17990 clocks; a build may "
                                "take at most 70 % (12593 clocks)", 0), 0u) << s.problems[0];
  EXPECT_TRUE(hls::dtmf_top_clock_budget(streaming, 18000000, 12000, 12593).ok());
}

// The default scene on the iCEBreaker: the clock the flow picks (18 MHz,
// for the measured load) also holds the bound within 90 % of the frame.
TEST(FrameBound, DefaultSceneKeepsItsBoundWithinTheLimit) {
  const fpga::CoreClock c = fpga::choose_core_clock(fpga::find_board("icebreaker"), base(),
                                                    fpga::LoadPolicy::Stress);
  const auto b = hls::dtmf_top_clock_budget(c.plan, c.clocking.clk_hz, c.engine_clocks,
                                            long(c.bound.total()));
  std::printf("icebreaker default: %ld Hz, frame %ld clocks, bound %llu (limit %ld)\n",
              c.clocking.clk_hz, b.frame_clocks, (unsigned long long)c.bound.total(),
              b.bound_limit_clocks);
  EXPECT_EQ(c.clocking.clk_hz, 18000000);
  EXPECT_TRUE(b.ok()) << (b.problems.empty() ? "" : b.problems[0]);
  EXPECT_EQ(c.bound.total(), hls::dtmf_frame_bound(c.plan).total());
}

}  // namespace

namespace {

// Builds whose measured load keeps up but whose bound exceeds 90 % of the
// frame are refused by the flow before any tool runs, naming the bound, its
// share, the frame and the limit: the frame engine asked for at the clocks
// the scale table's measured loads once chose (docs/scale_table.csv before
// the bound: the 32x32 ECP5 builds at 50 MHz, barrel shifter and neuron
// lanes, measured 49 778 and 48 021 of 50 015 and 49 999 clocks a frame;
// on the UP5K at 18 MHz, bit-serial with the neuron unit, a 9x9 skin,
// whose measured load fits 17 990 clocks): each bound printed with the
// failure. Left to the board, the
// clock (and on the ECP5 the datapath) is one at which the bound holds
// (tests/fpga/bitstream_flow_test.cpp CoreClock).
TEST(FrameBound, ScaleTableBuildsBeyondTheLimitAreRefused) {
  struct Probe {
    const char* board;
    const char* device;
    int n;
    double fs;
    long clk_hz;
  };
  for (const Probe& p : {Probe{"ulx3s", "85k", 32, 35000.0, 50000000},
                         Probe{"ulx3s", "85k", 32, 1e6, 50000000},
                         Probe{"icebreaker", "up5k", 9, 35000.0, 18000000}}) {
    fpga::FlowOptions o;
    o.source_dir = ESKIN_SOURCE_DIR;
    o.out_dir = testing::TempDir() + "/frame_bound_refused";
    o.load = fpga::LoadPolicy::Stress;
    o.clk_hz = p.clk_hz;
    o.datapath = 0;
    if (std::string(p.board) == "icebreaker") o.fast_shift = 0, o.neuron_unit = 1;  // as then built
    const fpga::FlowReport r =
        fpga::run_flow(fpga::find_board(p.board, p.device), fpga::scale_scene(base(), p.n, p.fs), o);
    std::printf("%s %dx%d at %g S/s, %ld Hz: measured %ld, bound %llu (frame %llu + command "
                "%llu) of %ld (limit %ld)\n%s\n",
                p.board, p.n, p.n, p.fs, r.clk_hz, r.engine_clocks,
                (unsigned long long)r.bound.total(), (unsigned long long)r.bound.frame,
                (unsigned long long)r.bound.command, r.budget.frame_clocks,
                r.budget.bound_limit_clocks, r.failure.c_str());
    EXPECT_FALSE(r.ran_tools);
    EXPECT_TRUE(r.bitstream.empty());
    EXPECT_LE(r.engine_clocks, r.budget.frame_clocks);  // the measurement alone keeps up
    EXPECT_GT(long(r.bound.total()), r.budget.bound_limit_clocks);
    EXPECT_EQ(r.failure.rfind("frame bound: frame_engine: the static bound of a frame and a "
                              "command, " + std::to_string(r.bound.total()) + " clocks, is ", 0),
              0u) << r.failure;
    EXPECT_NE(r.failure.find("of a frame of " + std::to_string(r.budget.frame_clocks) +
                             " clocks; a build may take at most 90 % (" +
                             std::to_string(r.budget.bound_limit_clocks) + " clocks)"),
              std::string::npos) << r.failure;
  }
}

}  // namespace

namespace {

// The scale table's rows carry the frame's clocks, the measured worst case
// and the static bound (CSV columns frame_clocks, engine_clocks,
// bound_clocks), and the Markdown table shows them with the frame's spare
// under the bound; rows written before those columns read as 0 and show
// "-".
TEST(FrameBound, ScaleTableCarriesTheBound) {
  fpga::ScaleRow a;
  a.target = "ecp5-85k";
  a.board = "ulx3s";
  a.device = "85k";
  a.sample_hz = 35000;
  a.rows = a.cols = 16;
  a.window = 64;
  a.step = 35;
  a.clk_hz = 50000000;
  a.fits = a.meets_timing = true;
  a.frame_clocks = 50015;
  a.engine_clocks = 17625;
  a.bound_clocks = 36878;
  const std::string csv = fpga::scale_csv({a});
  EXPECT_NE(csv.find(",50015,17625,36878,engine,\"\""), std::string::npos) << csv;
  const auto rows = fpga::parse_scale_csv(csv);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].frame_clocks, 50015);
  EXPECT_EQ(rows[0].engine_clocks, 17625);
  EXPECT_EQ(rows[0].bound_clocks, 36878);
  // (50015 - 36878) / 50015 = 26.3 % spare.
  const std::string md = fpga::scale_markdown(rows);
  EXPECT_NE(md.find("| 17625 / 36878 of 50015 (26 %) |"), std::string::npos) << md;
  // The header and a row from before the columns.
  const std::string old =
      "target,board,device,sample_hz,rows,cols,window,step,clk_hz,adc_clk_hz,shifter,neurons,"
      "fits,meets_timing,logic_used,logic_available,dsp_used,dsp_available,ram_used,"
      "ram_available,spram_used,seed,fmax_mhz,seconds,failure\n"
      "ecp5-85k,ulx3s,85k,35000,16,16,64,35,50000000,0,barrel,lanes,1,1,1,2,3,4,5,6,0,1,50.00,"
      "9,\"\"\n";
  const auto before = fpga::parse_scale_csv(old);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].bound_clocks, 0);
  EXPECT_EQ(before[0].seconds, 9);
  EXPECT_NE(fpga::scale_markdown(before).find("| 50.0 MHz | - |"), std::string::npos)
      << fpga::scale_markdown(before);
  EXPECT_FALSE(before[0].streaming);
  // The streaming datapath's rows name it (CSV datapath, the table's engine
  // column); the header before that column reads as the frame engine's, and
  // an unknown datapath is refused naming the line.
  a.streaming = true;
  a.engine = {true, false, false};
  const auto s = fpga::parse_scale_csv(fpga::scale_csv({a}));
  ASSERT_EQ(s.size(), 1u);
  EXPECT_TRUE(s[0].streaming);
  EXPECT_NE(fpga::scale_markdown(s).find("| streaming datapath (barrel shifter control plane) |"),
            std::string::npos)
      << fpga::scale_markdown(s);
  std::string no_dp = fpga::scale_csv({a});
  no_dp.replace(no_dp.find("bound_clocks,datapath,"), 22, "bound_clocks,");
  no_dp.replace(no_dp.find(",streaming,"), 11, ",");
  const auto e = fpga::parse_scale_csv(no_dp);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_FALSE(e[0].streaming);
  std::string bad = fpga::scale_csv({a});
  bad.replace(bad.find(",streaming,"), 11, ",chain,");
  try {
    fpga::parse_scale_csv(bad);
    ADD_FAILURE() << "datapath 'chain' accepted";
  } catch (const std::runtime_error& x) {
    EXPECT_NE(std::string(x.what()).find("line 2: expected datapath engine|streaming, got chain"),
              std::string::npos) << x.what();
  }
}

}  // namespace
