// How many clocks the frame engine of rtl/dtmf_top.v needs per frame for a
// plan, measured on its instruction-set model (ucode/frame_engine.h is clock
// exact against rtl/frame_engine.v) running the plan's microcode
// (ucode/dtmf_ucode.h) on the frames sdft_bank would deliver (the exact window
// sums of hls/sdft_bank.h). hls::dtmf_top_clock_budget() checks the result
// against STEP x the sample period.
//
// The microcode's time depends on the data (ghost filter loops, spikes,
// sparse packets) and on the commands, so this is a measurement, not a
// proof. Three figures:
//  - scene: the longest frame of a scene's own ADC samples (its presses and
//    slides), the workload the scene describes;
//  - stress: the longest frame of synthetic signals that drive every path
//    (or, when larger, the longest frame without its packets plus the
//    largest packets of any frame: EngineLoad::stress_bound)
//    hard (random levels, random on/off carriers, all carriers toggling,
//    steady full, steady quiet; 64 frames or more each) at the plan's mask
//    and decimations, and with the ghost filter each again with every
//    taxel made an active site before each frame (a taxel costs more when
//    it is one, and synthetic signals leave few);
//  - command: the longest command of docs/protocol.md §5, each accepted and
//    each reason of rejection, which delays the frame after it (commands
//    run between frames).
// On the streaming datapath the frame buffer holds the chain's magnitudes
// (hls/carrier_magnitude.h of the same window sums), and the ghost filter's
// sites live in the chain's mask, which no path of the control plane reads:
// no run with every taxel a site.
// The output FIFO always has room (every packet is written, none dropped:
// the slow case). tests/fpga/engine_load_test.cpp checks the scene figure
// against the clocked top model of tests/hls.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "eskin/dtmf_top_plan.h"

namespace eskin::fpga {

struct EngineLoad {
  uint64_t scene_clocks = 0;    // longest frame of the scene's samples
  int scene_frames = 0;         // frames of them (0: no samples given)
  uint64_t stress_clocks = 0;   // longest frame of the stress signals
  std::string stress_case;      // which signal
  uint64_t command_clocks = 0;  // longest command: start -> back at `wait`
  std::string command_case;
  int stress_frames = 0;
  // Each stress signal's longest frame, then each command's clocks.
  std::vector<std::pair<std::string, uint64_t>> cases;
  // The longest stress frame's clocks by microcode routine (named after
  // the HLS kernels: hls::dtmf_ucode_routines), most first; they add up to
  // stress_clocks (the last instruction's tail past the release aside).
  std::vector<std::pair<std::string, uint64_t>> stress_routines;
  // A frame's packets (routines `packets` and `status`: the decimated
  // amplitude and taxel packets, a spike window's close, the status) fall
  // on whichever frame the decimation counters give, so the signals' own
  // alignment may never put the largest on the longest frame; any skin
  // can. The most one stress frame took besides its packets, and the most
  // one frame's packets took: their sum bounds every alignment.
  uint64_t stress_other_clocks = 0, stress_packet_clocks = 0;
  uint64_t stress_bound() const {
    return std::max(stress_clocks, stress_other_clocks + stress_packet_clocks);
  }
  // The streaming datapath (DtmfDatapath::Streaming): the engine is the
  // chain's control plane, and the chain's own clocks a frame
  // (dtmf_chain_frame_clocks at the plan's mask: fixed latencies, not
  // measured) come on top of its step, as ucode/dtmf_frame_bound.h adds
  // them. 0 on the frame engine.
  uint64_t chain_clocks = 0;
  uint64_t stress_total() const { return stress_bound() + command_clocks + chain_clocks; }
  uint64_t scene_total() const { return scene_clocks + chain_clocks; }
};

// Throws std::invalid_argument when the plan's engine image does not fit
// the frame engine's address space (DMEM 2^15 words, KROM 2^12 words,
// microcode kDtmfImemWords), naming the numbers.
// `scene_x`: the scene's samples as dtmf_top takes them (12-bit codes minus
// 2048), sample 0 first after the carriers are loaded; may be empty.
EngineLoad measure_engine_load(const hls::DtmfTopPlan& plan, const std::vector<int32_t>& scene_x);

}  // namespace eskin::fpga
