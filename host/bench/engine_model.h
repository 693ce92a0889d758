// The frame engine's clocks per frame for any plan: the frame_engine
// instruction-set model (ucode/frame_engine.h, clock-exact with
// rtl/frame_engine.v) running the plan's microcode (ucode/dtmf_ucode.h)
// against the top's IO ports as rtl/dtmf_top.v wires them, at run-time
// sizes: the DFT tokens of each frame from host/engine/exact_sdft.h (equal
// to sdft_bank's), frames by frame_capture's rule (the window full, then
// every STEP samples), an output FIFO the link drains. The run-time
// counterpart of tests/ucode/dtmf_top_model.h, for the latency benchmark's
// model check and the trade study's latency column.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "eskin/dtmf_top_plan.h"

namespace eskin::bench {

// One frame, clocks counted from the clock its frame became pending.
struct FrameClocks {
  uint32_t t = 0;             // its newest sample
  int64_t first_out = -1;     // the engine's first output byte (-1: none)
  int64_t done = -1;          // it released the frame (-1: not yet)
  uint32_t bytes = 0;         // output bytes written for it
};

class EngineCycleModel {
 public:
  // clk_per_sample: FPGA clocks per ADC sample (CLK_HZ / SAMPLE_HZ).
  EngineCycleModel(const hls::DtmfTopPlan& plan, long clk_per_sample);
  ~EngineCycleModel();
  // One 12-bit ADC code; the engine then runs one sample period.
  void sample(uint16_t code);
  const std::vector<FrameClocks>& frames() const;
  uint32_t frame_overruns() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

// The longest engine time (frame pending -> released) of the plan's frames
// over 12-bit codes.
int64_t max_engine_clocks(const hls::DtmfTopPlan& plan, const std::vector<uint16_t>& codes,
                          long clk_per_sample);

}  // namespace eskin::bench
