// uart_tx: the clock-exact C++ model of rtl/uart_tx.v (8N1, CPB clocks a
// bit), a part of the `cycle` fidelity level (docs/vboard.md). s_ready is
// combinational on the registers; tx is the register. Held to the
// Verilated RTL clock by clock in tests/rtl/uart_tx_test.cpp.
#pragma once

#include <cstdint>
#include <stdexcept>

namespace eskin::cycle {

class UartTx {
 public:
  // CPB = round(CLK_HZ / BAUD), as the RTL derives it.
  UartTx(uint64_t clk_hz, uint64_t baud) : cpb_(uint32_t((clk_hz + baud / 2) / baud)) {
    if (cpb_ < 2) throw std::invalid_argument("UartTx: fewer than 2 clocks a bit");
  }
  uint32_t clocks_per_bit() const { return cpb_; }

  bool tx() const { return tx_; }
  bool s_ready() const { return !busy_ || (bitn_ == 9 && cnt_ == cpb_ - 1); }

  void reset() {
    busy_ = false;
    tx_ = true;
    cnt_ = 0;
    bitn_ = 0;
    shreg_ = 0;
  }
  void clock(bool s_valid, uint8_t s_data) {
    if (s_valid && s_ready()) {
      busy_ = true;
      tx_ = false;
      shreg_ = s_data;
      cnt_ = 0;
      bitn_ = 0;
    } else if (busy_) {
      if (cnt_ == cpb_ - 1) {
        cnt_ = 0;
        if (bitn_ == 9) {
          busy_ = false;
        } else {
          tx_ = bitn_ == 8 ? true : (shreg_ & 1u) != 0;
          shreg_ = uint8_t(shreg_ >> 1);
          ++bitn_;
        }
      } else {
        ++cnt_;
      }
    }
  }

 private:
  uint32_t cpb_;
  bool busy_ = false, tx_ = true;
  uint32_t cnt_ = 0;
  int bitn_ = 0;  // 0 start, 1..8 data, 9 stop
  uint8_t shreg_ = 0;
};

}  // namespace eskin::cycle
