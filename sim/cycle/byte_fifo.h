// byte_fifo: the clock-exact C++ model of rtl/byte_fifo.v, one of the
// parts of the virtual board's `cycle` fidelity level (docs/vboard.md,
// "Fidelity levels"). Same registers, same update at each rising edge; the
// combinational outputs (free, the load decision) are functions of the
// registers and this clock's inputs. tests/rtl/byte_fifo_test.cpp holds it
// to the Verilated RTL clock by clock.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace eskin::cycle {

class ByteFifo {
 public:
  explicit ByteFifo(int depth) : depth_(uint32_t(depth)), mem_(size_t(depth), 0) {
    if (depth < 2 || depth > 32768 || (depth & (depth - 1)) != 0)
      throw std::invalid_argument("ByteFifo: DEPTH must be a power of two in 2..32768");
  }

  // Registered outputs.
  bool out_valid() const { return out_valid_; }
  uint8_t out_data() const { return out_data_; }
  uint16_t overflows() const { return overflows_; }
  // Combinational.
  uint32_t used() const { return (wp_ - rp_) & (2 * depth_ - 1); }
  uint16_t free() const { return uint16_t(depth_ - used()); }

  void reset() {
    wp_ = rp_ = 0;
    out_valid_ = false;
    overflows_ = 0;
  }
  // One rising edge with this clock's inputs.
  void clock(bool in_valid, uint8_t in_data, bool out_ready) {
    const uint32_t u = used();
    const bool full = u == depth_;
    const bool load = u != 0 && (!out_valid_ || out_ready);
    if (load) out_data_ = mem_[rp_ & (depth_ - 1)];  // a slot the write below never is
    if (in_valid && !full) mem_[wp_ & (depth_ - 1)] = in_data;
    if (in_valid) {
      if (!full) wp_ = (wp_ + 1) & (2 * depth_ - 1);
      else if (overflows_ != 0xFFFF) ++overflows_;
    }
    if (load) {
      rp_ = (rp_ + 1) & (2 * depth_ - 1);
      out_valid_ = true;
    } else if (out_ready) {
      out_valid_ = false;
    }
  }

 private:
  uint32_t depth_;
  std::vector<uint8_t> mem_;
  uint32_t wp_ = 0, rp_ = 0;  // AW + 1 bits
  bool out_valid_ = false;
  uint8_t out_data_ = 0;
  uint16_t overflows_ = 0;
};

}  // namespace eskin::cycle
