// A scene's DTMF chain (hls/dtmf_chain.h) set up as the FPGA top runs it,
// and the scene's ADC codes as the AD7476A delivers them: what every test
// that compares host-link packets with "what the FPGA sends" starts from
// (tests/rtl/dtmf_top_test.cpp, tests/stream/).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "hls/dtmf_chain.h"
#include "hls/izhikevich_layer_config.h"
#include "hls/sdft_bank_config.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace eskin::testing {

// Host-side chain configuration from a scene: carriers as phase increments,
// conductance taxels (recip from the full-carrier window magnitude in 10-bit
// code units: N/2 * full_carrier_lsb), the scene's neuron at dt = step / fs.
template <class Chain>
typename Chain::Config chain_config(const eskin::sim::Scene& sc, int step, uint16_t decim,
                                    uint8_t mask) {
  typename Chain::Config c;
  const auto f = sc.skin.carrier_freqs_hz();
  const double fs = sc.skin.adc.rate_hz;
  c.sdft.carriers = int(f.size());
  for (size_t k = 0; k < f.size(); ++k) c.sdft.inc[k] = eskin::hls::sdft_phase_increment(f[k], fs);
  c.taxel.rows = uint8_t(sc.skin.rows);
  c.taxel.cols = uint8_t(sc.skin.cols);
  c.taxel.mode = eskin::hls::TaxelMode::Conductance;
  c.taxel.recip_shift = 12;
  const double full = sc.decoder.window / 2.0 * sc.skin.full_carrier_lsb();
  c.taxel.recip = uint16_t(std::lround(std::ldexp(1.0, 15 + 12) / full));
  c.neuron = eskin::hls::make_izhikevich_config(
      eskin::hls::izhikevich_fixed_preset(sc.neuron.preset), step * 1000.0 / fs,
      sc.neuron.input_scale / 32768.0, 1);
  c.step = step;
  c.decim_amp = decim;
  c.decim_tax = decim;
  c.mask = mask;
  return c;
}

// The world model's codes as 12-bit AD7476A codes (left aligned).
inline std::vector<uint16_t> scene_codes12(const eskin::sim::Scene& sc) {
  eskin::sim::WorldModel world(sc);
  std::vector<uint16_t> c;
  for (int v : world.all_codes()) c.push_back(uint16_t(v << (12 - sc.skin.adc.bits)));
  return c;
}

}  // namespace eskin::testing
