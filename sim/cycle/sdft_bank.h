// sdft_bank: the clock-exact C++ model of rtl/sdft_bank.v (one lane: the
// sliding DFT whose carriers share one multiplier, 6 clocks a carrier), a
// part of the `cycle` fidelity level (docs/vboard.md). The control is the
// RTL's state machine, clock for clock (IDLE, OLD, C1..C6 per carrier, C6
// waiting for the output register); the arithmetic is hls/sdft_bank.h's
// (the RTL is bit-exact with it: tests/rtl/sdft_bank_test.cpp) applied per
// carrier with the increments the configuration port wrote, so a sample
// taken between two carrier writes uses the mix the RTL's RAM holds. A
// sample's sums are all computed at its handshake: no configuration write
// can come before its last carrier is out (cfg_ready is IDLE only).
// in_ready and cfg_ready are combinational on the registers; the output
// port is a register. Held to the Verilated RTL clock by clock, with
// frame_capture behind it, in tests/rtl/dft_capture_test.cpp.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "hls/sdft_bank.h"

namespace eskin::cycle {

// Sizes at run time (K_MAX, N, ACC_W: a top's plan); the formats are the
// top's (XW 12, CW 16, TW 10, FB 0), whose sine table and rounding are
// hls::SdftBank's.
class SdftBank {
  // The kernel's table, index and rounding depend on XW, CW, TW and FB only.
  using Hls = hls::SdftBank<1, 2, 12, 16, 10, 32, 0>;

 public:
  SdftBank(int k_max, int n, int acc_w)
      : n_(n), acc_w_(acc_w), kd_(depth(k_max)), inc_(size_t(kd_)), ph_(size_t(kd_)),
        re_(size_t(kd_)), im_(size_t(kd_)), win_(size_t(n)) {
    if (k_max < 1 || k_max > 256 || n < 2 || acc_w < 14 || acc_w > 32)
      throw std::invalid_argument("SdftBank: K_MAX 1..256, N >= 2, ACC_W 14..32");
  }

  // in_ready depends on this clock's cfg_valid (a carrier write goes first).
  bool in_ready(bool cfg_valid) const { return state_ == kIdle && configured_ && !cfg_valid; }
  bool cfg_ready() const { return state_ == kIdle; }
  bool out_valid() const { return out_valid_; }
  uint8_t out_k() const { return out_k_; }
  int32_t out_re() const { return out_re_; }
  int32_t out_im() const { return out_im_; }
  bool out_last() const { return out_last_; }

  void reset() {
    state_ = kIdle;
    configured_ = false;
    klast_ = 0;
    k_ = 0;
    out_valid_ = false;
    clear();
  }

  // One rising edge. x: the signed sample (XW bits) offered with in_valid.
  void clock(bool in_valid, int32_t x, bool in_skip, bool cfg_valid, uint8_t cfg_k,
             uint32_t cfg_inc, bool cfg_last, bool out_ready) {
    const bool in_fire = in_valid && in_ready(cfg_valid);
    const bool cfg_fire = cfg_valid && cfg_ready();
    const bool out_free = !out_valid_ || out_ready;
    const bool advance = state_ == kC6 && (out_free || skip_);
    // The output register: carrier k's token when C6 moves on.
    if (advance && !skip_) {
      out_valid_ = true;
      out_k_ = uint8_t(k_);
      out_re_ = re_[size_t(k_)];
      out_im_ = im_[size_t(k_)];
      out_last_ = k_ == klast_;
    } else if (out_ready) {
      out_valid_ = false;
    }
    if (cfg_fire) inc_[size_t(cfg_k & (kd_ - 1))] = cfg_inc;  // the RAM's KB address bits
    switch (state_) {
      case kIdle:
        if (cfg_fire && cfg_last) {
          klast_ = cfg_k & (kd_ - 1);
          configured_ = true;
          clear();
        } else if (in_fire) {
          skip_ = in_skip;
          compute(x);
          state_ = kOld;
        }
        break;
      case kOld: state_ = kC1; break;
      case kC1: case kC2: case kC3: case kC4: case kC5:
        state_ = State(state_ + 1);
        break;
      default:  // kC6
        if (advance) {
          state_ = k_ == klast_ ? kIdle : kC1;
          k_ = k_ == klast_ ? 0 : k_ + 1;
        }
        break;
    }
  }

 private:
  enum State : uint8_t { kIdle, kOld, kC1, kC2, kC3, kC4, kC5, kC6 };
  static int depth(int k_max) {  // the RTL's carrier RAM depth, 2^clog2(K_MAX), at least 2
    int d = 2;
    while (d < k_max) d *= 2;
    return d;
  }
  int32_t wrap_acc(int64_t v) const {  // modulo 2^ACC_W, sign-extended
    return int32_t(int64_t(uint64_t(v) << (64 - acc_w_)) >> (64 - acc_w_));
  }

  void clear() {  // cfg_last: window, phases and sums read as 0 from now on
    for (auto& w : win_) w = 0;
    for (int k = 0; k < kd_; ++k) re_[size_t(k)] = im_[size_t(k)] = 0, ph_[size_t(k)] = 0;
    wp_ = 0;
  }
  // The sample's new sums and phases for carriers 0..klast, as C1..C6 write them.
  void compute(int32_t x_in) {
    const int32_t x = Hls::wrap_sample(x_in);
    const int32_t x_old = win_[size_t(wp_)];
    win_[size_t(wp_)] = x;
    wp_ = wp_ + 1 == n_ ? 0 : wp_ + 1;
    for (int k = 0; k <= klast_; ++k) {
      const uint32_t th = ph_[size_t(k)], inc = inc_[size_t(k)];
      const uint32_t in = Hls::index(th), io = Hls::index(th - inc * uint32_t(n_));
      re_[size_t(k)] = wrap_acc(int64_t(re_[size_t(k)]) + Hls::term(x, Hls::cosine(in)) -
                                     Hls::term(x_old, Hls::cosine(io)));
      im_[size_t(k)] = wrap_acc(int64_t(im_[size_t(k)]) + Hls::term(x, -Hls::sine(in)) -
                                     Hls::term(x_old, -Hls::sine(io)));
      ph_[size_t(k)] = th + inc;
    }
  }

  State state_ = kIdle;
  bool configured_ = false, skip_ = false;
  int klast_ = 0, k_ = 0;
  int n_, acc_w_, kd_;
  std::vector<uint32_t> inc_, ph_;
  std::vector<int32_t> re_, im_, win_;
  int wp_ = 0;
  bool out_valid_ = false, out_last_ = false;
  uint8_t out_k_ = 0;
  int32_t out_re_ = 0, out_im_ = 0;
};

}  // namespace eskin::cycle
