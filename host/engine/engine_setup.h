// Scene -> engine configuration: the FPGA build a scene gets, as the
// runtime EngineConfig of host/engine/dtmf_engine.h. Everything the top is
// built with (sizes, widths, step, decimation, demixing, taxel, ghost,
// synapse and neuron constants)
// comes from common/eskin/dtmf_top_plan.h's plan, the one place the RTL builds and
// the HLS chain take theirs from; this file only copies it across, so the
// engine follows the top when the plan changes.
#pragma once

#include <cstdint>
#include <vector>

#include "eskin/neuron_config.h"
#include "eskin/skin_config.h"
#include "eskin/dtmf_top_plan.h"
#include "host/engine/dtmf_engine.h"

namespace eskin::engine {

// The top's plan for a skin decoded with `dec` and `neuron` (clk_hz: the
// FPGA clock, which sets only the top's CLK_HZ; spikes: the neuron layers
// run).
hls::DtmfTopPlan top_plan(const SkinConfig& skin, const DecoderConfig& dec,
                          const NeuronConfig& neuron, bool spikes,
                          long clk_hz = hls::kDtmfTopClkHz);

// The plan re-derived for another frame step (samples; the neuron dt, the
// ghost lookback and the demixer's per-frame rotation follow, as
// make_dtmf_top_plan derives them) and packet decimation (frames, both
// streams; 0: the plan's rule for the link). Throws like the plan.
hls::DtmfTopPlan with_step(const hls::DtmfTopPlan& plan, int step, int decim = 0);

// The engine running exactly that build (hls::chain_config's fields).
EngineConfig engine_config(const hls::DtmfTopPlan& plan);

// The skin's codes as the FPGA sees them (12-bit, left aligned).
std::vector<uint16_t> codes12(const std::vector<int>& codes, int adc_bits);

}  // namespace eskin::engine
