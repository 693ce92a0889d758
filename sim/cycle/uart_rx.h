// uart_rx: the clock-exact C++ model of rtl/uart_rx.v (8N1, two-flop
// synchroniser, start bit re-checked half a bit in, one-byte holding
// register), a part of the `cycle` fidelity level (docs/vboard.md). Every
// output is a register. Held to the Verilated RTL clock by clock in
// tests/rtl/uart_rx_test.cpp.
#pragma once

#include <cstdint>
#include <stdexcept>

namespace eskin::cycle {

class UartRx {
 public:
  UartRx(uint64_t clk_hz, uint64_t baud) : cpb_(uint32_t((clk_hz + baud / 2) / baud)) {
    if (cpb_ < 2) throw std::invalid_argument("UartRx: fewer than 2 clocks a bit");
    half_ = cpb_ / 2;
  }

  bool m_valid() const { return m_valid_; }
  uint8_t m_data() const { return m_data_; }
  bool frame_err() const { return frame_err_; }
  bool overrun() const { return overrun_; }

  void reset() {
    rx_s1_ = rx_s2_ = true;
    state_ = kIdle;
    cnt_ = 0;
    bitn_ = 0;
    shreg_ = 0;
    m_valid_ = false;
    m_data_ = 0;
    frame_err_ = overrun_ = false;
  }

  void clock(bool rx, bool m_ready) {
    const bool s2 = rx_s2_;
    const bool valid_before = m_valid_;
    frame_err_ = false;
    overrun_ = false;
    if (valid_before && m_ready) m_valid_ = false;
    switch (state_) {
      case kIdle:
        if (!s2) {
          state_ = kStart;
          cnt_ = 0;
        }
        break;
      case kStart:
        if (cnt_ == half_ - 1) {
          cnt_ = 0;
          bitn_ = 0;
          state_ = s2 ? kIdle : kData;
        } else {
          ++cnt_;
        }
        break;
      case kData:
        if (cnt_ == cpb_ - 1) {
          cnt_ = 0;
          shreg_ = uint8_t((s2 ? 0x80 : 0) | (shreg_ >> 1));
          if (bitn_ == 7) state_ = kStop;
          bitn_ = (bitn_ + 1) & 7;
        } else {
          ++cnt_;
        }
        break;
      case kStop:
        if (cnt_ == cpb_ - 1) {
          cnt_ = 0;
          if (!s2) {
            frame_err_ = true;
            state_ = kWait;
          } else {
            state_ = kIdle;
            if (valid_before && !m_ready) {
              overrun_ = true;
            } else {
              m_valid_ = true;
              m_data_ = shreg_;
            }
          }
        } else {
          ++cnt_;
        }
        break;
      default:  // kWait: the line must return high first
        if (s2) state_ = kIdle;
        break;
    }
    rx_s2_ = rx_s1_;
    rx_s1_ = rx;
  }

 private:
  enum State : uint8_t { kIdle, kStart, kData, kStop, kWait };
  uint32_t cpb_, half_;
  bool rx_s1_ = true, rx_s2_ = true;
  State state_ = kIdle;
  uint32_t cnt_ = 0;
  int bitn_ = 0;
  uint8_t shreg_ = 0;
  bool m_valid_ = false;
  uint8_t m_data_ = 0;
  bool frame_err_ = false, overrun_ = false;
};

}  // namespace eskin::cycle
