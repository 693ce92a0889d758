// The per-core halves of run_flow (host/fpga/flow.h), shared by a mixed
// build: the DTMF core's plan (flow.cpp) and the Hall or mixed build
// (hall_flow.cpp). Internal to host/fpga.
#pragma once

#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "host/fpga/board.h"
#include "host/fpga/flow.h"
#include "host/fpga/tool_run.h"
#include "sim/scene.h"

namespace eskin::fpga {

// The DTMF core up to the tools: the plan at the chosen clock (its figures
// into r), its microcode and constants written into OUT as
// dtmf_scene.ucode.hex / .krom.hex; `clk` and dtmf_top's parameters out.
// False, with r.failure naming each budget missed, when no clock keeps up.
// own_adc_clock as in choose_core_clock (false for mixed_top, one clock).
bool plan_dtmf_core(const Board& b, const sim::Scene& scene, const FlowOptions& opt,
                    FlowReport& r, Clocking& clk, std::vector<hls::VerilogParam>& params,
                    bool own_adc_clock);

// A Hall or mixed build (r.core) up to the tools, after r's board fields
// are set: the Hall spec, the pins, the clock (and, mixed, the DTMF plan),
// the core module and the constraints written into OUT, and the tools' run
// in `t`. False, with r.failure and the numbers, when the board has too few
// pins or (mixed) no clock keeps up.
bool prepare_hall_build(const Board& b, const sim::Scene& scene, const FlowOptions& opt,
                        FlowReport& r, ToolRun& t);
// prepare_hall_build, then the tools.
void run_hall_flow(const Board& b, const sim::Scene& scene, const FlowOptions& opt,
                   FlowReport& r);

}  // namespace eskin::fpga
