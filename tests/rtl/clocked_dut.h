// A Verilated rtl/ module driven from a test: every module has `clk` and a
// synchronous active-high `rst`, and its streams start idle.
#pragma once

#include <cstdint>

template <class V>
struct ClockedDut {
  V m;
  uint64_t cycle = 0;  // rising edges so far

  // One rising edge; inputs set before the call are sampled at it.
  void tick() {
    m.clk = 0;
    m.eval();
    m.clk = 1;
    m.eval();
    ++cycle;
  }
  // Two cycles of reset with the input stream idle and the output stalled.
  void reset() {
    m.rst = 1;
    m.in_valid = 0;
    m.out_ready = 0;
    tick();
    tick();
    m.rst = 0;
  }
};
