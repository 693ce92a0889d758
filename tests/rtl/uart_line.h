// Both directions of an 8N1 UART line at exactly `cpb` clocks per bit, for
// benches that clock a Verilated top one cycle at a time: bytes queued for
// the FPGA's uart_rx come out of tx_level() bit by bit, and the FPGA's
// uart_txd fed to rx_sample() is decoded by sampling the middle of each bit
// (a start bit first seen at cycle s: bit j at s + cpb j + cpb/2).
#pragma once

#include <cstdint>
#include <vector>

class UartLine {
 public:
  explicit UartLine(int cpb) : cpb_(uint64_t(cpb)) {}

  // Host -> FPGA.
  void send(const std::vector<uint8_t>& bytes) {
    for (uint8_t b : bytes) {
      bits_.push_back(0);
      for (int i = 0; i < 8; ++i) bits_.push_back((b >> i) & 1);
      bits_.push_back(1);
    }
  }
  bool sending() const { return pos_ < bits_.size() * cpb_; }
  // The line level for the next clock (idle high).
  int tx_level() { return sending() ? bits_[pos_++ / cpb_] : 1; }

  // FPGA -> host: one call per clock; returns true when a byte completed
  // (byte(), its start bit's cycle start_cycle(), stop bit ok stop_ok()).
  bool rx_sample(int level, uint64_t cycle) {
    if (!busy_) {
      if (level == 0) busy_ = true, start_ = cycle, byte_ = 0;
      return false;
    }
    const uint64_t off = cycle - start_;
    if (off % cpb_ != cpb_ / 2) return false;
    const uint64_t j = off / cpb_;
    if (j >= 1 && j <= 8) byte_ |= uint8_t(level << (j - 1));
    if (j < 9) return false;
    busy_ = false;
    stop_ok_ = level == 1;
    return true;
  }
  uint8_t byte() const { return byte_; }
  uint64_t start_cycle() const { return start_; }
  bool stop_ok() const { return stop_ok_; }

 private:
  uint64_t cpb_;
  std::vector<uint8_t> bits_;
  size_t pos_ = 0;
  bool busy_ = false, stop_ok_ = true;
  uint64_t start_ = 0;
  uint8_t byte_ = 0;
};
