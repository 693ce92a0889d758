// An 8N1 UART receiver on a line level sampled at least once per bit
// time: it starts at a falling edge, samples each bit in its middle (a
// start bit read high there was a glitch), and counts a stop bit read
// low as a framing error (the byte is still given). The USB-serial
// bridge's receiver (usb_serial.h) and the virtual board's taps on the
// FPGA's uart_txd pin (line_faults.h, board faults) are each one of these.
#pragma once

#include <cstdint>

namespace eskin::vboard {

class UartRxModel {
 public:
  // The bit time (ns; 0: not listening), used from the next sample on.
  void set_bit_ns(double b) { bit_ns_ = b; }
  double bit_ns() const { return bit_ns_; }
  // The level at time t (ns, non-decreasing): the byte whose stop bit this
  // sample read, else -1.
  int sample(double t, bool level) {
    if (!busy_) {
      if (level || bit_ns_ == 0) return -1;  // idle, or nobody listening
      busy_ = true;
      start_ = t;
      bit_ = 0;
      byte_ = 0;
      next_ = t + 0.5 * bit_ns_;
      return -1;
    }
    if (t < next_) return -1;
    if (bit_ == 0) {
      if (level) busy_ = false;  // a glitch, not a start bit
    } else if (bit_ <= 8) {
      byte_ |= uint8_t(int(level) << (bit_ - 1));
    } else {
      busy_ = false;
      if (!level) ++framing_errors_;
      return byte_;
    }
    ++bit_;
    next_ = start_ + (bit_ + 0.5) * bit_ns_;
    return -1;
  }
  uint64_t framing_errors() const { return framing_errors_; }

 private:
  double bit_ns_ = 0, start_ = 0, next_ = 0;
  bool busy_ = false;
  int bit_ = 0;
  uint8_t byte_ = 0;
  uint64_t framing_errors_ = 0;
};

}  // namespace eskin::vboard
