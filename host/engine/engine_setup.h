// Scene -> engine configuration: the FPGA build a scene gets (dtmf_top's
// parameters), as the runtime EngineConfig of host/engine/dtmf_engine.h.
// This is the one place that knows how the top is parameterised for a scene;
// when the top changes, only this file and its table follow.
//
// Rules (rtl/dtmf_top.v, docs/fpga.md):
//   codes      the skin's ADC codes left-aligned to the AD7476A's 12 bits
//              (code << (12 - bits)); XW = 12 (code - 2048)
//   sdft       N = decoder.window, CW 16, TW 10, FB 0, ACC_W = XW + 1 + ceil(log2 N)
//   magnitude  MAG_W 16, MAG_SHIFT = 12 - bits (window sums in skin code units)
//   taxels     conductance g (UQ1.15): recip = round(2^(15 + rs) / (N/2 *
//              full_carrier_lsb)), rs = 12 (lowered while recip >= 2^16)
//   neurons    hls::make_izhikevich_config(preset, step / fs in ms,
//              input_scale / 32768, x_shift 1)
#pragma once

#include <cstdint>
#include <vector>

#include "eskin/neuron_config.h"
#include "eskin/skin_config.h"
#include "host/engine/dtmf_engine.h"

namespace eskin::engine {

struct EngineChoice {
  int step = 1;             // samples per processing step
  uint16_t decim = 35;      // packets (and spike windows) every decim steps
  uint8_t mask = 7;         // amplitudes | taxels | spikes
};

// Throws ConfigError / std::invalid_argument naming the field.
EngineConfig engine_config(const SkinConfig& skin, const DecoderConfig& dec,
                           const NeuronConfig& neuron, const EngineChoice& choice);

// The skin's codes as the FPGA sees them (12-bit, left aligned).
std::vector<uint16_t> codes12(const std::vector<int>& codes, int adc_bits);

}  // namespace eskin::engine
