// common/eskin/dtmf_top_plan.h's output FIFO depth (OUT_DEPTH of rtl/dtmf_top.v).
// frame_engine writes a packet only when the whole of it fits the FIFO, and
// drops it otherwise (rtl/ucode/dtmf_chain.fe, pkt_begin), so a packet longer
// than the FIFO could never be sent. The lengths here come from
// docs/protocol.md section 4, not from the plan: header 7 bytes (type, t,
// len); TAXELS_DENSE 2 + 2T; TAXELS_SPARSE 4T with every taxel lit.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "eskin/dtmf_top_plan.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"

namespace {

using namespace eskin;

hls::DtmfTopPlan plan_for(const std::string& scene, long clk_hz) {
  return hls::make_dtmf_top_plan(sim::dtmf_top_spec(sim::load_scene(ESKIN_SOURCE_DIR "/scenes/" + scene), clk_hz));
}

TEST(DtmfTopPlan, TheDefaultSceneKeepsItsOneEbrPairFifo) {
  // 29 of the UP5K's 30 EBRs are in use (docs/fpga.md): the default
  // scene's FIFO must stay at 512 bytes.
  const auto p = hls::make_dtmf_top_plan(
      sim::dtmf_top_spec(sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml")));
  EXPECT_EQ(p.out_depth, 512);
}

TEST(DtmfTopPlan, EveryTaxelPacketOfALargeSkinFitsTheFifoWhole) {
  for (const char* scene : {"staggered10x10.yaml", "skin32x32.yaml"}) {
    const auto p = plan_for(scene, 96000000);
    const int t = p.R * p.C;
    EXPECT_GE(p.out_depth, 7 + 2 + 2 * t) << scene << ": dense taxels";
    EXPECT_GE(p.out_depth, 7 + 4 * t) << scene << ": sparse, all lit";
    EXPECT_EQ(p.out_depth & (p.out_depth - 1), 0) << "a power of two (byte_fifo)";
    EXPECT_LT(p.out_depth, 2 * std::max(512, hls::longest_packet_bytes(p)))
        << "no larger than it must be";
  }
}

}  // namespace

TEST(DtmfTopPlan, TheAdcPlanRefusesAPeriodWithoutCsHighTime) {
  // AD7476A t1 >= 10 ns (docs/protocol.md): CS must go high between
  // conversions. At a 10 MHz ADC clock and 312.5 kS/s the period is 32
  // clocks = 32 H: acquisition (4 clocks, 400 ns >= 250) and quiet time
  // (1 clock, 100 ns >= 86) both pass, but no clock of CS high is left, so
  // rtl/adc_ad7476.v refuses the set at elaboration (lint test
  // lint.adc_ad7476_rejects_illegal_parameters_t1 is the same rule at 12 MHz).
  const std::string bad = hls::dtmf_top_adc_problem(312500.0, 10000000);
  EXPECT_NE(bad.find("0 ns of CS high (>= 10 ns)"), std::string::npos) << bad;
  // One clock more (33, 303.03 kS/s) leaves 100 ns of CS high: accepted.
  EXPECT_EQ(hls::dtmf_top_adc_problem(10000000.0 / 33, 10000000), "");
}
