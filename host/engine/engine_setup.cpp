#include "host/engine/engine_setup.h"

#include <cmath>
#include <stdexcept>

#include "hls/izhikevich_layer_config.h"
#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"

namespace eskin::engine {

EngineConfig engine_config(const SkinConfig& skin, const DecoderConfig& dec,
                           const NeuronConfig& neuron, const EngineChoice& choice) {
  if (skin.adc.bits < 1 || skin.adc.bits > 12)
    throw ConfigError("skin.adc.bits", "expected 1..12 for the FPGA path (AD7476A, 12 bits), got " +
                                           std::to_string(skin.adc.bits));
  EngineConfig c;
  c.rows = skin.rows;
  c.cols = skin.cols;
  c.sdft.n = dec.window;
  c.sdft.xw = 12;
  c.sdft.acc_w = hls::sdft_min_acc_width(dec.window, c.sdft.xw);
  c.mag_shift = 12 - skin.adc.bits;
  const double fs = skin.adc.rate_hz;
  for (double f : skin.carrier_freqs_hz()) c.inc.push_back(hls::sdft_phase_increment(f, fs));
  c.taxel.rows = uint8_t(skin.rows);
  c.taxel.cols = uint8_t(skin.cols);
  c.taxel.mode = hls::TaxelMode::Conductance;
  const double full = dec.window / 2.0 * skin.full_carrier_lsb();
  int rs = 12;
  while (rs > 0 && std::lround(std::ldexp(1.0, 15 + rs) / full) > 65535) --rs;
  c.taxel.recip_shift = uint8_t(rs);
  c.taxel.recip = uint16_t(std::min(65535L, std::lround(std::ldexp(1.0, 15 + rs) / full)));
  c.neuron = hls::make_izhikevich_config(hls::izhikevich_fixed_preset(neuron.preset),
                                         choice.step * 1000.0 / fs, neuron.input_scale / 32768.0,
                                         1);
  c.step = choice.step;
  c.decim_amp = c.decim_tax = choice.decim;
  c.mask = choice.mask;
  return c;
}

std::vector<uint16_t> codes12(const std::vector<int>& codes, int adc_bits) {
  std::vector<uint16_t> out(codes.size());
  const int sh = 12 - adc_bits;
  for (size_t i = 0; i < codes.size(); ++i) out[i] = uint16_t(codes[i] << sh);
  return out;
}

}  // namespace eskin::engine
