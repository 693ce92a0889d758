// The FPGA top's spec (common/eskin/dtmf_top_plan.h) for a scene: the skin's
// sizes, carriers, ADC and window, whether the carriers need demixing (any
// off a DFT bin centre), the ghost thresholds, the neurons and whether the
// scene wants spikes, and the FPGA clock.
#pragma once

#include <cmath>

#include "eskin/dtmf_top_plan.h"
#include "sim/scene.h"

namespace eskin::sim {

inline hls::DtmfTopSpec dtmf_top_spec(const Scene& sc, long clk_hz = hls::kDtmfTopClkHz) {
  hls::DtmfTopSpec s;
  s.rows = sc.skin.rows;
  s.cols = sc.skin.cols;
  s.carrier_hz = sc.skin.carrier_freqs_hz();
  s.sample_hz = sc.skin.adc.rate_hz;
  s.adc_bits = sc.skin.adc.bits;
  s.full_carrier_lsb = sc.skin.full_carrier_lsb();
  s.window = sc.decoder.window;
  s.demix = false;
  for (double f : s.carrier_hz) {
    const double bin = f * s.window / s.sample_hz;
    s.demix = s.demix || std::fabs(bin - std::round(bin)) > 1e-9;
  }
  s.ghost_onset_g = sc.decoder.ghost_onset;
  s.ghost_release_g = sc.decoder.ghost_threshold;
  s.spikes = sc.outputs.spikes;
  s.neuron_preset = sc.neuron.preset;
  s.neuron_change = sc.neuron.input == NeuronInput::RectifiedChange;
  s.neuron_input_scale = sc.neuron.input_scale;
  s.layer2_preset = sc.neuron.layer2.preset;
  s.layer2_centre = sc.neuron.layer2.centre;
  s.layer2_surround = sc.neuron.layer2.surround;
  s.clk_hz = clk_hz;
  return s;
}

}  // namespace eskin::sim
