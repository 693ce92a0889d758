// Scene -> engine configuration: the FPGA build a scene gets, as the
// runtime EngineConfig of host/engine/dtmf_engine.h. Everything the top is
// built with (sizes, widths, step, decimation, taxel and neuron constants)
// comes from hls/dtmf_top_config.h's plan, the one place the RTL builds and
// the HLS chain take theirs from; this file only copies it across, so the
// engine follows the top when the plan changes.
#pragma once

#include <cstdint>
#include <vector>

#include "eskin/neuron_config.h"
#include "eskin/skin_config.h"
#include "hls/dtmf_top_config.h"
#include "host/engine/dtmf_engine.h"

namespace eskin::engine {

// The top's plan for a skin decoded with `dec` and `neuron` (clk_hz: the
// FPGA clock; spikes: whether the build runs the neuron layer's budget).
hls::DtmfTopPlan top_plan(const SkinConfig& skin, const DecoderConfig& dec,
                          const NeuronConfig& neuron, bool spikes, long clk_hz = 12000000);

// The plan with another processing step (samples) and packet decimation
// (steps; 0: about one packet per ms, the plan's rule); the neuron constants
// (dt = step / fs) follow as make_dtmf_top_plan derives them. Throws like
// the plan.
hls::DtmfTopPlan with_step(const hls::DtmfTopPlan& plan, int step, int decim = 0);

// The engine running exactly that build. mask: amplitudes | taxels | spikes.
EngineConfig engine_config(const hls::DtmfTopPlan& plan, uint8_t mask = 7);

// The same with another step and packet decimation (neuron dt follows the
// step); for trade studies and decoding at another frame rate.
EngineConfig engine_config(const hls::DtmfTopPlan& plan, int step, uint16_t decim,
                           uint8_t mask);

// The skin's codes as the FPGA sees them (12-bit, left aligned).
std::vector<uint16_t> codes12(const std::vector<int>& codes, int adc_bits);

}  // namespace eskin::engine
