// The static worst-case bound (ucode/frame_bound.h) of the DTMF
// microprogram (rtl/ucode/dtmf_chain.fe) assembled for a plan: a frame, a
// command, and what a frame's clocks must hold. host/fpga/engine_load.h
// measures the same three on the instruction-set model; the measured worst
// case must stay below this bound (tests/fpga/frame_bound_test.cpp).
//
// Its assumptions are the measurement's: the plan's neuron constants (the
// counts of izhikevich_layer's shifts by constant words: the image's NSH*
// symbols), its taxel decimation (a spike window's events: SPKWIN), its
// output mask (sparse taxel packets or none: SPARSE) and the commands of
// docs/protocol.md (payloads up to the longest type's: CMD_PAYLOAD): the
// commands that change those (SET_NEURON, SET_DECIMATION, SET_OUTPUT_MASK)
// can take a frame past the bound (frame_any, command_any below). Everything else is any data: every path of
// every frame, every packet the mask may enable, every loop at its most.
#pragma once

#include <cstdint>

#include "eskin/dtmf_top_plan.h"
#include "ucode/frame_bound.h"

namespace eskin::hls {

struct DtmfFrameBound {
  // From `main`'s wait taking EV_FRAME_PENDING (its one clock with the
  // event there) through the frame's work back to that wait (the frame's
  // release, IO_FRAME_DONE, comes before it); on the streaming datapath
  // (its release is the header, IO_HEADER) with the chain's clocks added.
  uint64_t frame = 0;
  // From the same wait taking EV_CMD_AVAIL through the longest command
  // (docs/protocol.md §5, any type and length the command FIFO can hold,
  // accepted or rejected) back to it.
  uint64_t command = 0;
  // What a frame's clocks must hold: commands run between frames, so a
  // frame may wait for one command begun just before it came
  // (host/fpga/engine_load.h's stress_total, the same rule).
  uint64_t total() const { return frame + command; }
  // The same without the plan's assumptions: izhikevich_layer's shift
  // counts at the most SET_NEURON accepts (neuron_params), a spike window
  // of MAXSPK events (any SET_DECIMATION), sparse packets (any
  // SET_OUTPUT_MASK), and a command
  // frame as long as the command FIFO holds (kDtmfCmdFifoBytes: a junk
  // type or length is drained byte by byte before it is rejected). Not
  // what a build is checked against; what a host can make of it.
  uint64_t frame_any = 0, command_any = 0;
  uint64_t total_any() const { return frame_any + command_any; }
  // The streaming datapath (DtmfDatapath::Streaming): the chain's own
  // clocks a frame (dtmf_chain_frame_clocks, at the plan's mask and at any),
  // included in frame and frame_any: the control plane's step and the
  // chain's are added, as if none overlapped (the chain's taxels run while
  // the engine sends AMPLITUDES and status). 0 on the frame engine.
  uint64_t chain = 0, chain_any = 0;
};

// rtl/dtmf_top.v's command FIFO (cmd_decoder DEPTH): a committed frame,
// type, seq, len (2 bytes) and payload, fits it whole.
constexpr int kDtmfCmdFifoBytes = 512;

// The wait latencies the bound takes (fe_bound::Options::wait_clocks): the
// main wait 1 (the analysis starts when the event is there); EV_IZ_DONE the
// neuron unit's (its start registered from the U write: kIzhikevichUnitClocks
// + 2 B clocks after the starting `out` at most) or the lanes' (the last
// start's write-back, IzhikevichLanesPort::kLaneWriteBack + 1), each less
// the clocks since the latest start (wait_starts: the unit's x_prev and U
// writes, the lanes' x writes).
fe_bound::Options dtmf_frame_bound_options(const DtmfTopPlan& plan);

// Throws fe_bound::BoundError naming the source line of a loop it cannot
// bound, fe_asm::AsmError when the microcode does not assemble.
DtmfFrameBound dtmf_frame_bound(const DtmfTopPlan& plan);

}  // namespace eskin::hls
