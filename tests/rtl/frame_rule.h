// hls/dtmf_chain.h's frame rule, coded from its statement for the RTL
// tests of rtl/frame_capture.v: the N-th sample after reset or a carrier
// reload is a frame, then every STEP-th.
#pragma once

namespace frame_rule {

struct FrameRule {
  int n = 0, step = 0;
  int filled = 0, phase = 0;
  FrameRule(int window, int samples_per_frame) : n(window), step(samples_per_frame) {}
  void restart() { filled = 0; }
  bool next() {  // is the next sample a frame?
    if (filled < n) {
      phase = 0;
      return ++filled == n;
    }
    phase = phase + 1 == step ? 0 : phase + 1;
    return phase == 0;
  }
};

}  // namespace frame_rule
