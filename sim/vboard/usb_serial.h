// The board's USB-serial bridge (the FT2232H beside the iCE40 on the
// iCEBreaker) as seen from the FPGA's UART pins. It runs at the baud rate
// the host program set on its serial port, not at the FPGA's:
//   FPGA -> host: a UART receiver samples uart_txd (8N1) in the middle of
//     each bit at the host's rate; each byte goes to the host, with the
//     time its stop bit was sampled.
//   host -> FPGA: the host's bytes go out on uart_rxd as real 8N1 bits at
//     the host's rate, back to back.
// At equal rates every byte arrives intact; at different rates the bytes
// come out wrong on both sides, as on real hardware (the board reports the
// mismatch). Times are in ns; call sample_txd()/rxd_level() once per FPGA
// clock with non-decreasing times. A line model (line_faults.h), when set,
// drops and inserts characters where the bridge takes or gives them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "sim/vboard/line_faults.h"
#include "sim/vboard/uart_rx_model.h"

namespace eskin::vboard {

class UsbSerial {
 public:
  // Rate the host configured; takes effect at the next start bit.
  void set_baud(double baud) {
    bit_ns_ = baud > 0 ? 1e9 / baud : 0;
    rx_.set_bit_ns(bit_ns_);
  }
  bool configured() const { return bit_ns_ > 0; }

  // uart_txd level after the FPGA's clock edge at time t.
  void sample_txd(double t, bool level) {
    if (const int b = rx_.sample(t, level); b >= 0) deliver(uint8_t(b), t);
  }

  // Level the bridge drives on uart_rxd at time t.
  bool rxd_level(double t) {
    if (!tx_busy_) {
      if (to_fpga_.empty() || bit_ns_ == 0 || t < tx_not_before_) return true;
      tx_start_ = t;
      if (!take_for_fpga()) return true;
      tx_busy_ = true;
    }
    const int bit = int((t - tx_start_) / bit_ns_);
    if (bit == 0) return false;                   // start bit
    if (bit <= 8) return (tx_byte_ >> (bit - 1)) & 1;
    if (bit == 9) return true;                    // stop bit
    tx_busy_ = false;
    ++bytes_to_fpga_;
    return rxd_level(t);                          // next byte back to back
  }

  void queue_to_fpga(const uint8_t* p, size_t n) { to_fpga_.insert(to_fpga_.end(), p, p + n); }
  // No start bit before time t (ns): the line idles until then.
  void send_from(double t) { tx_not_before_ = t; }
  bool to_fpga_idle() const { return !tx_busy_ && to_fpga_.empty(); }

  // Bytes received from the FPGA and not yet handed to the host, with the
  // time (ns) each one's stop bit was sampled.
  std::vector<uint8_t>& to_host() { return to_host_; }
  std::vector<double>& byte_times() { return byte_times_; }

  uint64_t bytes_to_host() const { return bytes_to_host_; }
  uint64_t bytes_to_fpga() const { return bytes_to_fpga_; }
  uint64_t framing_errors() const { return rx_.framing_errors(); }
  // The byte on uart_rxd now (-1: the line idles).
  int byte_to_fpga_in_flight() const { return tx_busy_ ? int(tx_byte_) : -1; }

  void set_line(LineFaults* line) { line_ = line; }

 private:
  void deliver(uint8_t b, double t) {
    if (line_) {
      const LineFaults::Fate f = line_->fate(LineDir::to_host);
      if (f.inserted >= 0) {
        to_host_.push_back(uint8_t(f.inserted));
        byte_times_.push_back(t);
        ++bytes_to_host_;
      }
      if (f.drop) return;
    }
    to_host_.push_back(b);
    byte_times_.push_back(t);
    ++bytes_to_host_;
  }
  // The next character for uart_rxd into tx_byte_ (false: none left, all
  // dropped). An inserted one goes first; the host's byte stays queued.
  bool take_for_fpga() {
    while (!to_fpga_.empty()) {
      const LineFaults::Fate f = line_ ? line_->fate(LineDir::to_fpga) : LineFaults::Fate{};
      if (f.inserted >= 0) {
        tx_byte_ = uint8_t(f.inserted);
        if (f.drop) to_fpga_.pop_front();
        return true;
      }
      tx_byte_ = to_fpga_.front();
      to_fpga_.pop_front();
      if (!f.drop) return true;
    }
    return false;
  }

  LineFaults* line_ = nullptr;
  double bit_ns_ = 0;
  UartRxModel rx_;  // FPGA -> host
  std::vector<uint8_t> to_host_;
  std::vector<double> byte_times_;
  // host -> FPGA transmitter
  std::deque<uint8_t> to_fpga_;
  bool tx_busy_ = false;
  uint8_t tx_byte_ = 0;
  double tx_start_ = 0, tx_not_before_ = 0;
  uint64_t bytes_to_host_ = 0, bytes_to_fpga_ = 0;
};

}  // namespace eskin::vboard
