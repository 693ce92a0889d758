// frame_capture: the clock-exact C++ model of rtl/frame_capture.v (the
// frame decision per sample, the double-buffered frame the engine reads,
// pending / frame_t / overruns), a part of the `cycle` fidelity level
// (docs/vboard.md). smp_frame and tok_ready are combinational on the
// registers; rd_data is the registered read the engine samples one clock
// after it gave rd_addr. Held to the Verilated RTL clock by clock, behind
// the sdft_bank model, in tests/rtl/dft_capture_test.cpp.
#pragma once

#include <cstdint>
#include <vector>

namespace eskin::cycle {

class FrameCapture {
 public:
  // KS tokens a sample, W-bit tokens, window N, STEP samples a frame.
  FrameCapture(int ks, int w, int n, int step)
      : n_(n), step_(step), w_(w), tb_(ks > 1 ? clog2(ks) : 1),
        mem_(size_t(2) << tb_, {0, 0}) {}

  bool smp_frame() const { return filled_ != n_ ? filled_ + 1 == n_ : phase_ == step_ - 1; }
  bool tok_ready() const { return true; }
  // The engine's word (re at 2k, im at 2k + 1, sign-extended) it asked for
  // in the clock before.
  uint32_t rd_data() const { return uint32_t(rd_im_ ? rd_word_.second : rd_word_.first); }
  // The word the register will hold after this clock's edge, for an
  // address given now (what the engine's io_read at this clock returns).
  uint32_t read_now(uint8_t addr) const {
    const auto& e = mem_[(size_t(eb_) << tb_) | ((addr >> 1) & ((1u << tb_) - 1))];
    return uint32_t((addr & 1) ? e.second : e.first);
  }
  bool pending() const { return pending_; }
  uint32_t frame_t() const { return frame_t_; }
  uint16_t overruns() const { return overruns_; }

  void reset() {
    filled_ = phase_ = 0;
    cur_frame_ = false;
    cur_t_ = 0;
    eb_ = 0;
    widx_ = 0;
    pending_ = false;
    frame_t_ = 0;
    overruns_ = 0;
  }

  // One rising edge. re, im: the token's W-bit values (sign-extended).
  void clock(bool clr, bool smp_fire, uint32_t smp_t, bool tok_valid, bool tok_last, int32_t re,
             int32_t im, uint8_t rd_addr, bool done, bool clear) {
    const bool frame_now = smp_frame();
    const bool cur_frame = cur_frame_;
    const uint32_t cur_t = cur_t_;
    const int eb = eb_;
    // Buffer: the token into the bank the engine does not read; the read.
    rd_word_ = mem_[(size_t(eb) << tb_) | ((rd_addr >> 1) & ((1u << tb_) - 1))];
    rd_im_ = rd_addr & 1;
    if (cur_frame && tok_valid) mem_[(size_t(!eb) << tb_) | widx_] = {sext(re), sext(im)};
    // Frame decision.
    if (clr) {
      filled_ = 0;
      phase_ = 0;
    } else if (smp_fire) {
      cur_t_ = smp_t;
      cur_frame_ = frame_now;
      if (filled_ != n_) {
        ++filled_;
        phase_ = 0;
      } else {
        phase_ = phase_ == step_ - 1 ? 0 : phase_ + 1;
      }
    }
    // Handing over.
    const bool pending = pending_;
    if (clear) overruns_ = 0;
    if (done) pending_ = false;
    if (tok_valid) {
      widx_ = tok_last ? 0 : ((widx_ + 1) & ((1u << tb_) - 1));
      if (tok_last && cur_frame) {
        if (!pending || done) {
          eb_ = !eb;
          pending_ = true;
          frame_t_ = cur_t;
        } else if (overruns_ != 0xFFFF && !clear) {
          ++overruns_;
        }
      }
    }
  }

 private:
  static int clog2(int v) {
    int b = 0;
    while ((1 << b) < v) ++b;
    return b;
  }
  int32_t sext(int32_t v) const {  // W bits, sign-extended to 32 (rd_data)
    const uint32_t m = uint32_t(v) << (32 - w_);
    return int32_t(m) >> (32 - w_);
  }

  int n_, step_, w_, tb_;
  std::vector<std::pair<int32_t, int32_t>> mem_;  // {bank, k}: {re, im}
  int filled_ = 0, phase_ = 0;
  bool cur_frame_ = false;
  uint32_t cur_t_ = 0;
  int eb_ = 0;
  uint32_t widx_ = 0;
  std::pair<int32_t, int32_t> rd_word_{0, 0};
  bool rd_im_ = false;
  bool pending_ = false;
  uint32_t frame_t_ = 0;
  uint16_t overruns_ = 0;
};

}  // namespace eskin::cycle
