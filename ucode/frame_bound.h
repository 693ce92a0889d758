// frame_bound: a static worst-case bound of the frame engine's clocks over
// an assembled program (ucode/frame_engine_asm.h), proven from the listing
// instead of measured: every path, every loop at its bound, every
// instruction at its most clocks by the manual's timing (the fe:: timing
// functions of ucode/frame_engine.h that the clock-exact model runs by).
//
// Costs. An instruction costs its B clocks (fe::b_clocks) plus a bubble
// when any instruction that can come before it in the program leaves a
// hazard its cycle A cannot overlap (fe::overlaps); a `call` costs its own
// clock and the callee's bound through its `ret`. Data-dependent clocks take
// their largest value: a shift by a memory / P count its `.bound` (else 63,
// the hardware's largest), and the next instruction a bubble (a loaded count
// of 0 ends B in the loading clock); a `wait` the most B clocks its events
// can take (Options::wait_clocks, from the units' fixed latencies; less the
// clocks every path spends since the unit's start, Options::wait_starts),
// and the next instruction a bubble.
//
// Loops. Every cycle of the control flow must pass a counted branch:
//  - a `djnz xi` (i = 1..3) whose counter holds a constant N on every entry
//    into its loop (the nearest writes of xi before it, on every path, are
//    `ldx xi, N`) and that nothing in the loop but its djnz changes: the
//    djnz instructions on xi of one loop (one strongly connected part of
//    the flow) run at most N times in all per entry (N = 0: 65 536), so
//    they are taken at most N - 1 times;
//  - a branch with `.bound n` (the assembler's Program::bounds): taken at
//    most n times per entry into its loop (spike lists by MAXSPK, packet
//    and command loops, polling a unit with a fixed latency).
// A loop (innermost first) then costs (taken + 1) x its longest pass (from
// an entry or a counted branch's target to a counted branch), and counts
// as one step of the loop around it. A cycle with no counted branch is an
// error naming the branch that closes it, its address and its source line.
//
// The bound is sound for the program as the manual times it; it is loose
// where paths the data never takes together (a spike in every neuron, every
// packet in one frame) are added up. ESKIN_BOUND_DEBUG=1 in the environment
// prints each loop's and routine's bound to stderr: where the clocks go.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "ucode/frame_engine_asm.h"

namespace eskin::hls::fe_bound {

// What the program does not allow to bound, naming FILE:LINE, the address
// and the instruction.
class BoundError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Options {
  bool fast_shift = false;                   // the engine's FAST_SHIFT
  std::map<uint16_t, uint32_t> wait_clocks;  // a wait's most B clocks, by its event mask
  // The IO writes that start what a wait's event mask waits for, where its
  // wait_clocks are counted from the start: the event comes at most that
  // many B clocks after a wait that follows the starting `out` directly,
  // and the latest start is the one the event reports. A wait of such a
  // mask then costs max(its bubble + 1, wait_clocks - e), e the fewest
  // clocks any path can spend between the latest start and the wait (every
  // instruction at its fewest clocks, a callee at none; an `out` indexed by
  // x, a callee that may start, or a path back to reset ends the path as a
  // start).
  std::map<uint16_t, std::set<uint16_t>> wait_starts;
  std::string file = "program";              // the source's name in errors
};

// The most clocks from the instruction at `from` (its own clocks counted)
// until control first reaches an address of `stops` (their clocks not
// counted; `from` may be one: a path back to it ends there), for each stop
// some path reaches. A `ret` outside a call is an error.
std::map<uint32_t, uint64_t> longest_clocks(const fe_asm::Program& prog, uint32_t from,
                                            const std::set<uint32_t>& stops,
                                            const Options& opt);

// The most clocks of the routine at `entry`, from its first instruction
// through the `ret` that returns (not counting the call).
uint64_t routine_clocks(const fe_asm::Program& prog, uint32_t entry, const Options& opt);

}  // namespace eskin::hls::fe_bound
