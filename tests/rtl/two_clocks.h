// Two free-running clocks for a Verilated bench of a design with two clock
// domains (rtl/stream_cdc.v, rtl/dtmf_top.v with ADC_CLK_HZ): the rising
// edges of clocks A and B in time order, edges at the same instant
// together. Times in femtoseconds, so that the periods of the MHz clocks
// are whole numbers to 1 part in 10^7 (45 MHz: 22 222 222 fs) and no
// floating-point sum drifts.
#pragma once

#include <cmath>
#include <cstdint>

struct TwoClocks {
  struct Edge {
    bool a = false, b = false;  // which clocks rise at this instant
    int64_t t_fs = 0;
    double t_ns() const { return double(t_fs) * 1e-6; }
  };

  // b_phase_fs delays B's first edge (A's first is at period_a).
  TwoClocks(double a_hz, double b_hz, int64_t b_phase_fs = 0)
      : period_a(std::llround(1e15 / a_hz)), period_b(std::llround(1e15 / b_hz)),
        next_a_(period_a), next_b_(period_b + b_phase_fs) {}

  Edge next() {
    Edge e;
    e.t_fs = next_a_ < next_b_ ? next_a_ : next_b_;
    e.a = next_a_ == e.t_fs;
    e.b = next_b_ == e.t_fs;
    if (e.a) next_a_ += period_a;
    if (e.b) next_b_ += period_b;
    return e;
  }

  const int64_t period_a, period_b;

 private:
  int64_t next_a_, next_b_;
};
