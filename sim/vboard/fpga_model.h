// The FPGA top as the virtual board sees it: one clock cycle at a time,
// pins in and out: the ADC's SPI pins (rtl/dtmf_top.v), the I2C buses and
// DRDY lines (rtl/hall_top.v), the UART. A top leaves the pins it does not
// have alone. Implemented over the Verilated SystemC model in
// vboard_main.cpp (DTMF top) and vboard_hall_main.cpp (Hall top), which are
// compiled per FPGA parameter set.
#pragma once

#include <cstdint>
#include <string>

namespace eskin::vboard {

struct FpgaInputs {
  bool reset = false;    // the board's reset button held (rst_n low)
  bool adc_sdata = false;
  bool uart_rxd = true;  // idle high
  uint64_t scl_i = 0, sda_i = 0;  // I2C line levels, bit b: bus b
  uint64_t drdy = 0;              // bit s: sensor slot s's DRDY
};

struct FpgaOutputs {
  bool adc_cs_n = true;
  bool adc_sclk = true;
  bool uart_txd = true;
  uint64_t scl_oe = 0, sda_oe = 0;  // I2C pull-downs, bit b: bus b
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
