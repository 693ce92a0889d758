// Host-side, not synthesised: the one place that derives the configuration
// of the DTMF FPGA top (rtl/dtmf_top.v) and of its bit-exact spec
// (hls/dtmf_chain.h) from a skin's numbers. Every build of the top — tests,
// the virtual board, `eskin bitstream`, benchmarks — takes its Verilog
// parameters from dtmf_top_params(), and every HLS chain its configuration
// from chain_config(), so the two can never disagree.
//
// The input is plain numbers (DtmfTopSpec): hls/ includes nothing of the
// rest of the tree; sim/dtmf_top_spec.h fills the spec from a scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hls/carrier_demix_config.h"
#include "hls/dtmf_chain.h"
#include "hls/izhikevich_layer_config.h"
#include "hls/sdft_bank_config.h"

namespace eskin::hls {

// What a skin asks of the FPGA top.
struct DtmfTopSpec {
  int rows = 3, cols = 3;
  std::vector<double> carrier_hz;  // rows first, then columns
  double sample_hz = 35000.0;
  int adc_bits = 10;               // the scene's ADC; codes reach the top left-aligned to 12
  double full_carrier_lsb = 155.15;  // one full carrier at the ADC, in adc_bits LSB
  int window = 32;                 // N
  bool demix = true;               // carriers off bin centres: joint LS demixing
  bool ghost = true;               // multi-touch ghost correction
  double ghost_onset_g = 0.05, ghost_release_g = 0.05, ghost_pair_tol_g = 0.02;
  double frame_ms = 1.0;           // one frame (and neuron step) per frame_ms
  bool spikes = true;              // the scene wants spikes: neurons on
  std::string neuron_preset = "RA";
  bool neuron_change = false;      // receptor input: rectified change (else level)
  double neuron_input_scale = 10.0;  // taxel g (0..1) -> neuron input units
  std::string layer2_preset = "RS";
  double layer2_centre = 20.0, layer2_surround = -4.0;
  long clk_hz = 12000000;          // FPGA clock
  long baud = 3000000;
};

// A Verilog parameter override: value in Verilog syntax (e.g. "16'd35").
struct VerilogParam {
  std::string name, value;
};

namespace dtmf_top_detail {
inline int clog2(long v) {
  int b = 0;
  while ((1L << b) < v) ++b;
  return b;
}
}  // namespace dtmf_top_detail

// Derived plan: sizes, widths, step and every constant of the chain.
template <class S>
struct DtmfTopPlan {
  DtmfTopSpec spec;
  DtmfChainConfig<S> chain;
  double full_mag = 0;   // one full carrier in magnitude units
  int lookback = 1;      // ghost filter history, frames
};

constexpr int kSynapseFrac = 8;  // synapse weights: int16, 8 fraction bits

// Throws std::invalid_argument naming the field when the spec cannot be
// built (sizes, carriers, demixing, neuron constants).
template <class S>
DtmfTopPlan<S> make_dtmf_top_plan(const DtmfTopSpec& s) {
  constexpr int K = S::K;
  DtmfTopPlan<S> p;
  p.spec = s;
  auto& c = p.chain;
  if (s.rows != S::R || s.cols != S::C)
    throw std::invalid_argument("skin.rows/cols: the chain is built for " + std::to_string(S::R) +
                                "x" + std::to_string(S::C) + ", got " + std::to_string(s.rows) +
                                "x" + std::to_string(s.cols));
  if (s.window != S::N)
    throw std::invalid_argument("decoder.window: the chain is built for N = " +
                                std::to_string(S::N) + ", got " + std::to_string(s.window));
  if (int(s.carrier_hz.size()) != K)
    throw std::invalid_argument("skin.carriers: expected " + std::to_string(K) +
                                " frequencies, got " + std::to_string(s.carrier_hz.size()));
  if (s.adc_bits < 1 || s.adc_bits > 12)
    throw std::invalid_argument("skin.adc.bits: expected 1..12 (AD7476A), got " +
                                std::to_string(s.adc_bits));
  c.step = int(std::lround(s.frame_ms * s.sample_hz / 1000.0));
  if (c.step < 1)
    throw std::invalid_argument("frame_ms: expected at least one sample per frame, got " +
                                std::to_string(s.frame_ms) + " ms");
  const double frame_ms = 1000.0 * c.step / s.sample_hz;
  // Carriers (+ the DC channel last when demixing).
  c.demix = s.demix;
  c.sdft.carriers = s.demix ? K + 1 : K;
  for (int k = 0; k < K; ++k) c.sdft.inc[k] = sdft_phase_increment(s.carrier_hz[size_t(k)], s.sample_hz);
  if (s.demix) {
    c.sdft.inc[K] = 0;
    const double gain = (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15);  // sdft_bank's G
    const auto st = make_carrier_demix_config<typename DtmfChain<S>::Demix>(
        s.carrier_hz, s.sample_hz, gain, c.demix_cfg, c.step, 0);
    if (!st.ok) throw std::invalid_argument("decoder.variant (demixing): " + st.message);
  }
  // One full carrier in magnitude units: window sum N/2 * A (12-bit codes);
  // demixing removes the bank's gain G, the plain bank keeps it.
  const double a12 = s.full_carrier_lsb * std::ldexp(1.0, 12 - s.adc_bits);
  p.full_mag = S::N / 2.0 * a12 / std::ldexp(1.0, S::MAG_SHIFT) *
               (s.demix ? 1.0 : (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15));
  if (!(p.full_mag >= 64 && p.full_mag < 65536))
    throw std::invalid_argument("skin.amp_gain: one full carrier is " + std::to_string(p.full_mag) +
                                " magnitude units, expected 64..65535 (resolution / 16 bits)");
  c.taxel.rows = uint8_t(S::R);
  c.taxel.cols = uint8_t(S::C);
  int rs = 0;
  while (std::ldexp(1.0, 15 + rs) / p.full_mag < 16384.0) ++rs;
  c.taxel.recip_shift = uint8_t(rs);
  c.taxel.recip = uint16_t(std::lround(std::ldexp(1.0, 15 + rs) / p.full_mag));
  // Ghost filter: thresholds from g units; lookback one window of frames.
  c.ghost = s.ghost;
  p.lookback = std::max(1, S::N / c.step);
  if (p.lookback > S::L_MAX)
    throw std::invalid_argument("decoder.window: ghost lookback " + std::to_string(p.lookback) +
                                " frames exceeds L_MAX " + std::to_string(S::L_MAX));
  auto mag_units = [&](double g, const char* field) {
    const double v = std::floor(g * p.full_mag);
    if (!(v >= 0 && v < 65536))
      throw std::invalid_argument(std::string(field) + ": expected 0 <= g < 1, got " +
                                  std::to_string(g));
    return uint16_t(v);
  };
  c.ghost_cfg.rows = uint8_t(S::R);
  c.ghost_cfg.cols = uint8_t(S::C);
  c.ghost_cfg.lookback = uint16_t(p.lookback);
  c.ghost_cfg.improved = true;
  c.ghost_cfg.onset = mag_units(s.ghost_onset_g, "decoder.ghost_onset");
  c.ghost_cfg.pair_tol = mag_units(s.ghost_pair_tol_g, "decoder.ghost_pair_tol");
  c.ghost_cfg.release = uint16_t(std::min(65535.0, std::ceil(s.ghost_release_g * 32768.0)));
  // Neurons: one step per frame.
  c.neurons = s.spikes;
  const double lsb = s.neuron_input_scale / 32768.0 / (s.neuron_change ? frame_ms : 1.0);
  c.neuron[0] = make_izhikevich_config(izhikevich_fixed_preset(s.neuron_preset), frame_ms, lsb, 1);
  c.neuron[0].input_change = s.neuron_change;
  c.neuron[1] = make_izhikevich_config(izhikevich_fixed_preset(s.layer2_preset), frame_ms,
                                       std::ldexp(1.0, -kSynapseFrac), 0);
  c.synapse.rows = uint8_t(S::R);
  c.synapse.cols = uint8_t(S::C);
  auto weight = [](double w, const char* field) {
    const double q = std::nearbyint(std::ldexp(w, kSynapseFrac));
    if (!(q >= -32768 && q <= 32767))
      throw std::invalid_argument(std::string(field) + ": expected |w| < 128, got " +
                                  std::to_string(w));
    return int16_t(q);
  };
  for (int d = 0; d < 9; ++d)
    c.synapse.w[d] = weight(d == 4 ? s.layer2_centre : s.layer2_surround,
                            d == 4 ? "neuron.layer2.centre" : "neuron.layer2.surround");
  c.decim_amp = 1;
  c.decim_tax = 1;
  c.mask = kMaskAmplitudes | kMaskTaxels | (s.spikes ? kMaskSpikes : 0);
  return p;
}

// "-GNAME=VALUE" arguments for verilator.
inline std::vector<std::string> verilator_g_args(const std::vector<VerilogParam>& ps) {
  std::vector<std::string> a;
  for (const auto& q : ps) a.push_back("-G" + q.name + "=" + q.value);
  return a;
}

// A wrapper module `name` with dtmf_top's ports that instantiates dtmf_top
// with the parameters (for Yosys, which takes no -G of packed vectors).
inline std::string dtmf_top_wrapper(const std::vector<VerilogParam>& ps,
                                    const std::string& name) {
  std::string v = "`default_nettype none\n// Generated by hls/dtmf_top_config.h.\nmodule " +
                  name +
                  " (\n    input wire clk, input wire rst_n,\n"
                  "    output wire adc_cs_n, output wire adc_sclk, input wire adc_sdata,\n"
                  "    output wire uart_txd, input wire uart_rxd);\n  dtmf_top #(\n";
  for (size_t j = 0; j < ps.size(); ++j)
    v += "      ." + ps[j].name + "(" + ps[j].value + ")" + (j + 1 < ps.size() ? ",\n" : "\n");
  v += "  ) u_top (.clk(clk), .rst_n(rst_n), .adc_cs_n(adc_cs_n), .adc_sclk(adc_sclk),\n"
       "      .adc_sdata(adc_sdata), .uart_txd(uart_txd), .uart_rxd(uart_rxd));\n"
       "endmodule\n`default_nettype wire\n";
  return v;
}

}  // namespace eskin::hls
