// The FPGA top as the virtual board sees it: one clock cycle at a time,
// pins in and out (rtl/dtmf_top.v's ports; outputs the board does not know
// are left alone). Implemented over the Verilated SystemC model in
// vboard_main.cpp, which is compiled per FPGA parameter set.
#pragma once

#include <cstdint>
#include <string>

namespace eskin::vboard {

struct FpgaInputs {
  bool adc_sdata = false;
  bool uart_rxd = true;  // idle high
};

struct FpgaOutputs {
  bool adc_cs_n = true;
  bool adc_sclk = true;
  bool uart_txd = true;
};

class FpgaModel {
 public:
  virtual ~FpgaModel() = default;
  // One clock: the inputs are sampled at the rising edge at time t_ps; the
  // outputs are those after it.
  virtual FpgaOutputs cycle(const FpgaInputs& in, uint64_t t_ps) = 0;
  // FST waveform of every signal from the next cycle on (GTKWave).
  virtual void open_trace(const std::string& path) = 0;
  virtual void close_trace() = 0;
};

}  // namespace eskin::vboard
