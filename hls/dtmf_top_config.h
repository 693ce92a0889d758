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

// The FPGA clock of the DTMF top: the iCEBreaker's 12 MHz oscillator x 3/2
// by the UP5K's PLL (VCO 576 MHz / 32). The top's place-and-route Fmax is
// about 20 MHz (the frame engine's operand -> 48-bit adder path); 18 MHz
// is the fastest PLL clock below it that divides into the 3 Mbaud link (6
// clocks per bit). The default scene's longest frame takes 16 900 of the
// 17 990 clocks between frames (docs/fpga.md).
constexpr long kDtmfTopClkHz = 18000000;

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
  long clk_hz = kDtmfTopClkHz;     // FPGA clock
  long baud = 3000000;
};

// A Verilog parameter override: value in Verilog syntax (e.g. "16'd35").
struct VerilogParam {
  std::string name, value;
};


// Derived plan: sizes, widths, step and every constant of the chain, for
// any skin size (host side, vectors); chain_config<S>() turns it into the
// fixed-size configuration of hls/dtmf_chain.h, dtmf_engine_image() (in
// hls/dtmf_engine_config.h) into the frame engine's constants.
struct DtmfTopPlan {
  DtmfTopSpec spec;
  int R = 0, C = 0, K = 0, T = 0, N = 0;
  int ks = 0;            // DFT channels: K (+ DC when demixing)
  int acc_w = 0;         // DFT window-sum width: 12 + 1 + ceil(log2 N)
  int mag_shift = 0;     // magnitude units: window sums >> mag_shift
  int step = 1;          // samples per frame
  int lookback = 1;      // ghost filter history, frames
  int max_spikes = 256;  // spike events per packet
  double full_mag = 0;   // one full carrier in magnitude units
  std::vector<uint32_t> inc;  // ks phase increments (DC last: 0)
  CarrierDemixTables demix;   // when spec.demix
  TaxelReconstructConfig taxel;
  GhostFilterConfig ghost;
  IzhikevichConfig neuron[2];  // layer 0 receptors, layer 1 weighted
  SynapseWeightsConfig synapse;
  uint16_t decim_amp = 1, decim_tax = 1, sparse_min = 0;
  uint8_t mask = 0;
};

constexpr int kSynapseFrac = 8;  // synapse weights: int16, 8 fraction bits

namespace dtmf_top_detail {
inline int clog2(long v) {
  int b = 0;
  while ((1L << b) < v) ++b;
  return b;
}
}  // namespace dtmf_top_detail

// Throws std::invalid_argument naming the field when the spec cannot be
// built (sizes, carriers, demixing, neuron constants).
inline DtmfTopPlan make_dtmf_top_plan(const DtmfTopSpec& s) {
  using dtmf_top_detail::clog2;
  DtmfTopPlan p;
  p.spec = s;
  p.R = s.rows, p.C = s.cols, p.K = s.rows + s.cols, p.T = s.rows * s.cols, p.N = s.window;
  if (s.rows < 1 || s.cols < 1 || p.K > 127 || p.T > 4096)
    throw std::invalid_argument("skin.rows/cols: expected 1..127 carriers and 1..4096 taxels, got " +
                                std::to_string(s.rows) + "x" + std::to_string(s.cols));
  if (int(s.carrier_hz.size()) != p.K)
    throw std::invalid_argument("skin.carriers: expected " + std::to_string(p.K) +
                                " frequencies, got " + std::to_string(s.carrier_hz.size()));
  if (s.adc_bits < 1 || s.adc_bits > 12)
    throw std::invalid_argument("skin.adc.bits: expected 1..12 (AD7476A), got " +
                                std::to_string(s.adc_bits));
  if (s.window < 4 || s.window > 4096)
    throw std::invalid_argument("decoder.window: expected 4..4096 samples, got " +
                                std::to_string(s.window));
  p.acc_w = 12 + 1 + clog2(p.N);
  p.mag_shift = clog2(p.N) > 5 ? clog2(p.N) - 5 : 0;
  p.step = int(std::lround(s.frame_ms * s.sample_hz / 1000.0));
  if (p.step < 1)
    throw std::invalid_argument("frame_ms: expected at least one sample per frame, got " +
                                std::to_string(s.frame_ms) + " ms");
  const double frame_ms = 1000.0 * p.step / s.sample_hz;
  // Carriers (+ the DC channel last when demixing).
  p.ks = s.demix ? p.K + 1 : p.K;
  for (double f : s.carrier_hz) p.inc.push_back(sdft_phase_increment(f, s.sample_hz));
  if (s.demix) {
    p.inc.push_back(0);
    const double gain = (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15);  // sdft_bank's G
    const auto st = carrier_demix_tables(s.carrier_hz, s.sample_hz, gain, p.N, 64, 10, 16, 16,
                                         14, p.step, 0, p.demix);
    if (!st.ok) throw std::invalid_argument("decoder.variant (demixing): " + st.message);
  }
  // One full carrier in magnitude units: window sum N/2 * A (12-bit codes);
  // demixing removes the bank's gain G, the plain bank keeps it.
  const double a12 = s.full_carrier_lsb * std::ldexp(1.0, 12 - s.adc_bits);
  p.full_mag = p.N / 2.0 * a12 / std::ldexp(1.0, p.mag_shift) *
               (s.demix ? 1.0 : (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15));
  if (!(p.full_mag >= 64 && p.full_mag < 65536))
    throw std::invalid_argument("skin.amp_gain: one full carrier is " + std::to_string(p.full_mag) +
                                " magnitude units, expected 64..65535 (resolution / 16 bits)");
  p.taxel.rows = uint8_t(p.R), p.taxel.cols = uint8_t(p.C);
  int rs = 0;
  while (std::ldexp(1.0, 15 + rs) / p.full_mag < 16384.0) ++rs;
  p.taxel.recip_shift = uint8_t(rs);
  p.taxel.recip = uint16_t(std::lround(std::ldexp(1.0, 15 + rs) / p.full_mag));
  // Ghost filter: thresholds from g units; lookback one window of frames.
  p.lookback = std::max(1, p.N / p.step);
  auto mag_units = [&](double g, const char* field) {
    const double v = std::floor(g * p.full_mag);
    if (!(v >= 0 && v < 65536))
      throw std::invalid_argument(std::string(field) + ": expected 0 <= g < 1, got " +
                                  std::to_string(g));
    return uint16_t(v);
  };
  p.ghost.rows = uint8_t(p.R), p.ghost.cols = uint8_t(p.C);
  p.ghost.lookback = uint16_t(p.lookback);
  p.ghost.improved = true;
  p.ghost.onset = mag_units(s.ghost_onset_g, "decoder.ghost_onset");
  p.ghost.pair_tol = mag_units(s.ghost_pair_tol_g, "decoder.ghost_pair_tol");
  p.ghost.release = uint16_t(std::min(65535.0, std::ceil(s.ghost_release_g * 32768.0)));
  // Neurons: one step per frame.
  const double lsb = s.neuron_input_scale / 32768.0 / (s.neuron_change ? frame_ms : 1.0);
  p.neuron[0] = make_izhikevich_config(izhikevich_fixed_preset(s.neuron_preset), frame_ms, lsb, 1);
  p.neuron[0].input_change = s.neuron_change;
  p.neuron[1] = make_izhikevich_config(izhikevich_fixed_preset(s.layer2_preset), frame_ms,
                                       std::ldexp(1.0, -kSynapseFrac), 0);
  p.synapse.rows = uint8_t(p.R), p.synapse.cols = uint8_t(p.C);
  auto weight = [](double w, const char* field) {
    const double q = std::nearbyint(std::ldexp(w, kSynapseFrac));
    if (!(q >= -32768 && q <= 32767))
      throw std::invalid_argument(std::string(field) + ": expected |w| < 128, got " +
                                  std::to_string(w));
    return int16_t(q);
  };
  for (int d = 0; d < 9; ++d)
    p.synapse.w[d] = weight(d == 4 ? s.layer2_centre : s.layer2_surround,
                            d == 4 ? "neuron.layer2.centre" : "neuron.layer2.surround");
  p.mask = kMaskAmplitudes | kMaskTaxels | (s.spikes ? kMaskSpikes : 0);
  // Packets every `decim` frames so that the link carries them with a 1.5x
  // margin (spikes, status, framing): amplitudes (10 + 2K bytes) and dense
  // taxels (12 + 2T) per frame against baud / 10 bytes per second.
  const double bytes = 1.5 * ((10.0 + 2 * p.K + 2) + (10.0 + 2 + 2.0 * p.T + 2));
  const double link = double(s.baud) / 10.0 * frame_ms / 1000.0;
  p.decim_amp = p.decim_tax = uint16_t(std::max(1.0, std::ceil(bytes / link)));
  return p;
}

// The fixed-size configuration of hls/dtmf_chain.h for the plan; the chain's
// sizes S must be the plan's.
template <class S>
DtmfChainConfig<S> chain_config(const DtmfTopPlan& p) {
  if (S::R != p.R || S::C != p.C || S::N != p.N)
    throw std::invalid_argument("chain_config: the chain is built for " + std::to_string(S::R) +
                                "x" + std::to_string(S::C) + " N " + std::to_string(S::N) +
                                ", the plan is " + std::to_string(p.R) + "x" +
                                std::to_string(p.C) + " N " + std::to_string(p.N));
  if (p.lookback > S::L_MAX || p.max_spikes != S::MAX_SPIKES)
    throw std::invalid_argument("chain_config: lookback / spike capacity differ from the chain's");
  DtmfChainConfig<S> c;
  c.sdft.carriers = p.ks;
  for (int k = 0; k < p.ks; ++k) c.sdft.inc[k] = p.inc[size_t(k)];
  c.demix = p.spec.demix;
  if (c.demix) {
    c.demix_cfg.carriers = p.K;
    for (int k = 0; k < p.K; ++k)
      c.demix_cfg.inc[k] = p.demix.inc[size_t(k)], c.demix_cfg.phase0[k] = p.demix.phase0[size_t(k)];
    for (size_t i = 0; i < p.demix.qsin.size(); ++i) c.demix_cfg.qsin[i] = p.demix.qsin[i];
    for (size_t i = 0; i < p.demix.coef.size(); ++i) c.demix_cfg.coef[i] = p.demix.coef[i];
  }
  c.taxel = p.taxel;
  c.ghost = p.spec.ghost;
  c.ghost_cfg = p.ghost;
  c.neurons = p.spec.spikes;
  c.neuron[0] = p.neuron[0];
  c.neuron[1] = p.neuron[1];
  c.synapse = p.synapse;
  c.step = p.step;
  c.decim_amp = p.decim_amp;
  c.decim_tax = p.decim_tax;
  c.sparse_min = p.sparse_min;
  c.mask = p.mask;
  return c;
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
