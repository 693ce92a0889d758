// A Verilated sliding DFT (rtl/sdft_bank.v or rtl/sdft_lanes.v: the same
// ports) as tests/rtl/sdft_bank_test.cpp and sdft_lanes_test.cpp drive it:
// held in reset for three clocks with every stream idle, its output token
// read as the HLS kernel's SdftBankToken, and a clock split into its low
// half (inputs set, then eval, then the checks) and its rising edge.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "hls/sdft_bank.h"

namespace sdft_port {

inline int32_t sext(uint32_t v, int bits) { return int32_t(v << (32 - bits)) >> (32 - bits); }

// n uniform XW-bit signed samples.
inline std::vector<int32_t> random_samples(int xw, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int32_t> d(-(1 << (xw - 1)), (1 << (xw - 1)) - 1);
  std::vector<int32_t> xs(n);
  for (auto& x : xs) x = d(rng);
  return xs;
}

template <class V, int ACC_W>
struct SdftPort {
  std::unique_ptr<V> m = std::make_unique<V>();
  uint64_t cycle = 0;  // rising edges so far

  SdftPort() {
    m->rst = 1;
    m->in_valid = m->cfg_valid = 0;
    m->out_ready = 0;
    for (int i = 0; i < 3; ++i) tick();
    m->rst = 0;
  }
  eskin::hls::SdftBankToken token() const {
    eskin::hls::SdftBankToken t;
    t.k = uint8_t(m->out_k);
    t.re = sext(m->out_re, ACC_W);
    t.im = sext(m->out_im, ACC_W);
    t.last = m->out_last;
    return t;
  }
  void tick() {
    m->clk = 0;
    m->eval();
    tick_high();
  }
  void tick_high() {
    m->clk = 1;
    m->eval();
    ++cycle;
  }
};

}  // namespace sdft_port
