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

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hls/izhikevich_layer_config.h"
#include "hls/sdft_bank_config.h"
#include "hls/taxel_reconstruct.h"

namespace eskin::hls {

// What a skin asks of the FPGA top.
struct DtmfTopSpec {
  int rows = 3, cols = 3;
  std::vector<double> carrier_hz;  // rows first, then columns
  double sample_hz = 35000.0;
  int adc_bits = 10;               // the scene's ADC; codes reach the top left-aligned to 12
  double full_carrier_lsb = 155.15;  // one full carrier at the ADC, in adc_bits LSB
  int window = 32;                 // N
  std::string neuron_preset = "RA";
  double neuron_input_scale = 10.0;  // taxel g (0..1) -> neuron input units
  bool spikes = true;              // the scene wants spikes
  long clk_hz = 12000000;          // FPGA clock
  long baud = 3000000;
};

// A Verilog parameter override: value in Verilog syntax (e.g. "16'd35").
struct VerilogParam {
  std::string name, value;
};

// Derived plan: what the top is built with (sizes, widths, step, constants).
struct DtmfTopPlan {
  DtmfTopSpec spec;
  int K = 0, T = 0, N = 0;
  int acc_w = 0, mag_shift = 0;
  int step = 1;          // samples per processing step
  int token_fifo = 0;    // DFT -> magnitude frame buffer (0: none)
  uint16_t decim = 35;   // amplitude/taxel packets and spike windows, in steps
  std::vector<uint32_t> carrier_inc;
  uint16_t tax_recip = 0;
  IzhikevichConfig neuron;
};

namespace dtmf_top_detail {
inline int clog2(long v) {
  int b = 0;
  while ((1L << b) < v) ++b;
  return b;
}
}  // namespace dtmf_top_detail

// Throws std::invalid_argument naming the field when the spec cannot be
// built (sizes, carriers, neuron constants).
inline DtmfTopPlan make_dtmf_top_plan(const DtmfTopSpec& s) {
  using dtmf_top_detail::clog2;
  DtmfTopPlan p;
  p.spec = s;
  p.K = s.rows + s.cols;
  p.T = s.rows * s.cols;
  p.N = s.window;
  if (s.rows < 1 || s.cols < 1 || p.K > 255)
    throw std::invalid_argument("skin.rows/cols: expected 1..254 carriers in all, got " +
                                std::to_string(p.K));
  if (int(s.carrier_hz.size()) != p.K)
    throw std::invalid_argument("skin.carriers: expected " + std::to_string(p.K) +
                                " frequencies, got " + std::to_string(s.carrier_hz.size()));
  if (s.adc_bits < 1 || s.adc_bits > 12)
    throw std::invalid_argument("skin.adc.bits: expected 1..12 (AD7476A), got " +
                                std::to_string(s.adc_bits));
  const int xw = 12;
  p.acc_w = xw + 1 + clog2(p.N);
  p.mag_shift = 12 - s.adc_bits;
  for (double f : s.carrier_hz) p.carrier_inc.push_back(sdft_phase_increment(f, s.sample_hz));
  // Conductance taxels: recip = 2^27 / (N/2 * full carrier), in adc_bits LSB.
  const double full = p.N / 2.0 * s.full_carrier_lsb;
  const double recip = std::nearbyint(std::ldexp(1.0, 15 + 12) / full);
  if (!(recip >= 1 && recip <= 65535))
    throw std::invalid_argument("skin.amp_gain: full-carrier magnitude " + std::to_string(full) +
                                " gives taxel reciprocal " + std::to_string(recip) +
                                ", expected 1..65535");
  p.tax_recip = uint16_t(recip);
  // Cycle budget per processed step (docs/fpga.md): magnitudes K x 26,
  // taxels 7 + T x 18, neurons T x 12; the step is the smallest number of
  // sample periods that holds the slowest stage.
  const long period = std::lround(double(s.clk_hz) / s.sample_hz);
  long busiest = std::max(26L * p.K, 7L + 18L * p.T);
  if (s.spikes) busiest = std::max(busiest, 12L * p.T);
  p.step = int((busiest + period - 1) / period);
  p.token_fifo = 26L * p.K > period ? 1 << clog2(p.K) : 0;
  const long per_ms = std::lround(s.sample_hz / 1000.0 / p.step);
  p.decim = uint16_t(std::max(1L, per_ms));
  p.neuron = make_izhikevich_config(izhikevich_fixed_preset(s.neuron_preset),
                                    p.step * 1000.0 / s.sample_hz,
                                    s.neuron_input_scale / 32768.0, 1);
  return p;
}

// The chain configuration (hls/dtmf_chain.h) of the same plan.
template <class Chain>
typename Chain::Config chain_config(const DtmfTopPlan& p) {
  typename Chain::Config c;
  if (Chain::K != p.K) throw std::invalid_argument("chain_config: chain K differs from the plan");
  c.sdft.carriers = p.K;
  for (int k = 0; k < p.K; ++k) c.sdft.inc[k] = p.carrier_inc[size_t(k)];
  c.taxel.rows = uint8_t(p.spec.rows);
  c.taxel.cols = uint8_t(p.spec.cols);
  c.taxel.mode = TaxelMode::Conductance;
  c.taxel.recip_shift = 12;
  c.taxel.recip = p.tax_recip;
  c.neuron = p.neuron;
  c.step = p.step;
  c.decim_amp = p.decim;
  c.decim_tax = p.decim;
  return c;
}

// dtmf_top's parameter overrides for the plan.
inline std::vector<VerilogParam> dtmf_top_params(const DtmfTopPlan& p) {
  auto i = [](long v) { return std::to_string(v); };
  auto d16 = [](long v) { return "16'd" + std::to_string(v); };
  std::string inc = std::to_string(32 * p.K) + "'h";
  for (int k = p.K - 1; k >= 0; --k) {
    char b[9];
    std::snprintf(b, sizeof b, "%08x", unsigned(p.carrier_inc[size_t(k)]));
    inc += b;
  }
  const IzhikevichConfig& n = p.neuron;
  return {
      {"CLK_HZ", i(p.spec.clk_hz)},       {"SAMPLE_HZ", i(std::lround(p.spec.sample_hz))},
      {"BAUD", i(p.spec.baud)},           {"R", i(p.spec.rows)},
      {"C", i(p.spec.cols)},              {"N", i(p.N)},
      {"ACC_W", i(p.acc_w)},              {"MAG_SHIFT", i(p.mag_shift)},
      {"CARRIER_INC", inc},               {"TAX_RECIP", i(p.tax_recip)},
      {"STEP", i(p.step)},                {"TOKEN_FIFO", i(p.token_fifo)},
      {"DECIM_AMP", d16(p.decim)},        {"DECIM_TAX", d16(p.decim)},
      {"V_INIT", i(n.v_init)},            {"U_INIT", i(n.u_init)},
      {"V_RESET", i(n.v_reset)},          {"U_JUMP", i(n.u_jump)},
      {"U_FRAC", i(n.u_frac)},            {"C_CONST", i(n.c_const)},
      {"M2", i(n.m2)},                    {"S2", i(n.s2)},
      {"M3", i(n.m3)},                    {"S3", i(n.s3)},
      {"M4", i(n.m4)},                    {"S4", i(n.s4)},
      {"GAIN", i(n.gain)},                {"GAIN_SHIFT", i(n.gain_shift)},
      {"X_SHIFT", i(n.x_shift)},
  };
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
