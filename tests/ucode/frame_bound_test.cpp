// ucode/frame_bound.h: the static bound on small programs whose clocks are
// counted by hand from docs/frame_engine.md ("Timing"), each also run on
// the instruction-set model where its path is the worst (the bound must
// equal the model's clocks there); its errors; the .bound directive; and
// the DTMF microprogram's bound for the default plan (every loop bounded).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <deque>
#include <string>

#include "eskin/dtmf_top_plan.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "ucode/dtmf_frame_bound.h"
#include "ucode/frame_bound.h"
#include "ucode/frame_engine.h"
#include "ucode/frame_engine_asm.h"

namespace {

using namespace eskin::hls;

fe_asm::Program asm_of(const std::string& src) {
  fe_asm::Options o;
  o.imem_words = 512;
  return fe_asm::assemble(src, "prog.fe", o);
}

uint64_t bound_to_end(const fe_asm::Program& p, bool fast = false,
                      std::map<uint16_t, uint32_t> waits = {}) {
  fe_bound::Options o;
  o.file = "prog.fe";
  o.fast_shift = fast;
  o.wait_clocks = std::move(waits);
  const auto r = fe_bound::longest_clocks(p, 0, {uint32_t(p.symbols.at("end"))}, o);
  return r.at(uint32_t(p.symbols.at("end")));
}

// IO reads answer from a queue (then 0); no events, except with a unit:
// a write to io[1] in clock c starts it, and its event 4 shows from clock
// c + kUnitDone on (the neuron unit's timing started by its U write, as
// ucode/engine_ports.h gives it: a wait right after the start then takes
// kUnitDone B clocks).
constexpr uint32_t kUnitDone = 15;
struct QueueIo {
  std::deque<uint32_t> reads;
  bool unit = false;
  uint64_t done = ~uint64_t(0);
  uint32_t io_read(uint16_t, uint64_t) {
    if (reads.empty()) return 0;
    const uint32_t v = reads.front();
    reads.pop_front();
    return v;
  }
  void io_write(uint16_t a, uint32_t, uint64_t clock) {
    if (unit && a == 1) done = clock + kUnitDone;
  }
  uint16_t events(uint64_t clock) { return unit && clock >= done ? 4 : 0; }
};

template <bool FAST>
struct Cfg {
  static constexpr int IW = 9, DW = 8, KW = 4;
  static constexpr bool FAST_SHIFT = FAST;
};

// The model's clocks from reset until the PC reaches `end`.
template <bool FAST = false>
uint64_t model_to_end(const fe_asm::Program& p, QueueIo io = {}, std::vector<uint32_t> krom = {}) {
  using Cfg = ::Cfg<FAST>;
  FrameEngine<Cfg> e;
  e.load_program(p.words.data(), uint32_t(p.words.size()));
  if (!krom.empty()) e.load_krom(krom.data(), uint32_t(krom.size()));
  e.reset();
  const uint32_t end = uint32_t(p.symbols.at("end"));
  e.run(io, 100000, [&](const FrameEngine<Cfg>& f) { return f.pc() == end; });
  EXPECT_EQ(e.pc(), end);
  return e.clocks();
}

// Straight code and a branch: the first instruction's cycle A is a clock
// of its own (nothing before it); j.ne reads A right after ld writes it
// (bubble); st does not read A; ld of DMEM right after st (bubble); shl 15
// 15 B clocks, min 2, rnd 12 13. With the add: 2 + 2 + 1 + 1 + 2 + 15 + 2
// + 13 = 38. Barrel shifter: shl 1, rnd 2: 38 - 14 - 11 = 13.
TEST(FrameBound, StraightCodeBubblesAndShifts) {
  const auto p = asm_of(
      "        ld    5\n"
      "        j.ne  skip\n"
      "        add   1\n"
      "skip:   st    [3]\n"
      "        ld    [3]\n"
      "        shl   15\n"
      "        min   k[0]\n"
      "        rnd   12\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(p), 38u);
  EXPECT_EQ(bound_to_end(p, true), 13u);
  // ld 5 is not 0: the model takes j.ne, skipping the add: one clock less.
  EXPECT_EQ(model_to_end(p), 37u);
  EXPECT_EQ(model_to_end<true>(p), 12u);
}

// A djnz loop with a constant count: ldx 2 (first), then 5 passes of ld,
// add, st, djnz (1 each: ld follows djnz, not st) = 2 + 20.
TEST(FrameBound, DjnzLoopWithAConstantCount) {
  const auto p = asm_of(
      "        ldx   x3, 5\n"
      "loop:   ld    [0 + x3]\n"
      "        add   1\n"
      "        st    [0 + x3]\n"
      "        djnz  x3, loop\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(p), 22u);
  EXPECT_EQ(model_to_end(p), 22u);
}

// Nested loops around a call. f: ld k[0] 1, shl k[0] with .bound 7: 1 + 7,
// ret after a loaded count 2 (no overlap) = 11; call 1 + 11; inner pass
// call + djnz = 13, x4 = 52; outer pass ldx + 52 + djnz = 54, x3 = 162;
// ldx x1 2 (first), j 1: 165. The model with KROM[0] = 7 takes that path
// less the ret's bubble (a loaded count of 7 is not 0: ret overlaps), 12
// clocks: the one the bound cannot know.
TEST(FrameBound, NestedLoopsCallAndALoadedShiftCount) {
  const auto p = asm_of(
      "        ldx   x1, 3\n"
      "outer:  ldx   x2, 4\n"
      "inner:  call  f\n"
      "        djnz  x2, inner\n"
      "        djnz  x1, outer\n"
      "        j     end\n"
      "f:      ld    k[0]\n"
      "        .bound 7\n"
      "        shl   k[0]\n"
      "        ret\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(p), 165u);
  EXPECT_EQ(model_to_end(p, {}, {7}), 165u - 12u);
  fe_bound::Options o;
  EXPECT_EQ(fe_bound::routine_clocks(p, uint32_t(p.symbols.at("f")), o), 11u);
  // Without the .bound the count is the hardware's largest, 63: f takes
  // 56 clocks more, 12 times.
  const auto q = asm_of(
      "        ldx   x1, 3\n"
      "outer:  ldx   x2, 4\n"
      "inner:  call  f\n"
      "        djnz  x2, inner\n"
      "        djnz  x1, outer\n"
      "        j     end\n"
      "f:      ld    k[0]\n"
      "        shl   k[0]\n"
      "        ret\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(q), 165u + 12u * 56u);
}

// A data-dependent loop with .bound 9: 10 passes of add (1) and j.gt
// (reads A after add: 2) after ld io 2 = 32; the model counting down from
// 10 takes it 9 times.
TEST(FrameBound, AnnotatedLoop) {
  const auto p = asm_of(
      "        ld    io[0]\n"
      "loop:   add   -1\n"
      "        .bound 9\n"
      "        j.gt  loop\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(p), 32u);
  QueueIo io;
  io.reads = {10};
  EXPECT_EQ(model_to_end(p, io), 32u);
}

// `.bound 10, outer`: the inner loop is taken 10 times in all per entry of
// the outer one (not per entry of its own). Outer pass: ld io 1, tax
// (reads A after ld) 2, one inner pass (nop, djnz) 2, djnz 1 = 6; x4 =
// 24; the inner loop's 10 more passes 20; ldx 2: 46. The model with
// counts 5, 3, 3, 3 (taken 4 + 2 + 2 + 2 = 10): the same.
TEST(FrameBound, AnnotatedLoopCountedPerEntryOfTheOuterLoop) {
  const auto p = asm_of(
      "        ldx   x1, 4\n"
      "outer:  ld    io[0]\n"
      "        tax   x2\n"
      "inner:  nop\n"
      "        .bound 10, outer\n"
      "        djnz  x2, inner\n"
      "        djnz  x1, outer\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(p), 46u);
  QueueIo io;
  io.reads = {5, 3, 3, 3};
  EXPECT_EQ(model_to_end(p, io), 46u);
  // Per entry of its own loop, the same count multiplies: 4 x (4 + 11 x 2).
  const auto q = asm_of(
      "        ldx   x1, 4\n"
      "outer:  ld    io[0]\n"
      "        tax   x2\n"
      "inner:  nop\n"
      "        .bound 10\n"
      "        djnz  x2, inner\n"
      "        djnz  x1, outer\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(q), 2u + 4u * (4u + 11u * 2u));
}

// A wait costs its events' bound (6 here) plus its cycle A (first: a clock
// of its own), and the next instruction a bubble: 7 + 2. sqrt after ld:
// a bubble and 51 B clocks (14 with the barrel shifter).
TEST(FrameBound, WaitAndSqrt) {
  const auto p = asm_of(
      "        wait  4\n"
      "        nop\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(p, false, {{4, 6}}), 9u);
  const auto r = asm_of(
      "        ld    100\n"
      "        sqrt\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(r), 2u + 1u + 51u);
  EXPECT_EQ(bound_to_end(r, true), 2u + 1u + 14u);
  EXPECT_EQ(model_to_end(r), 54u);
  EXPECT_EQ(model_to_end<true>(r), 17u);
}

// A wait for a unit's event counts from the unit's latest start
// (Options::wait_starts): kUnitDone B clocks right after the starting
// `out`, less the fewest clocks any path spends in between, at least one.
uint64_t unit_bound(const fe_asm::Program& p) {
  fe_bound::Options o;
  o.file = "prog.fe";
  o.wait_clocks = {{4, kUnitDone}};
  o.wait_starts = {{4, {1}}};
  const auto r = fe_bound::longest_clocks(p, 0, {uint32_t(p.symbols.at("end"))}, o);
  return r.at(uint32_t(p.symbols.at("end")));
}
uint64_t unit_model(const fe_asm::Program& p, std::deque<uint32_t> reads = {}) {
  QueueIo io;
  io.unit = true;
  io.reads = std::move(reads);
  return model_to_end(p, io);
}

// Straight code: the start's cycle A (a clock of its own) and B, n nops,
// the wait: 2 + n + max(1, kUnitDone - n), exactly the model's clocks,
// for every n from a wait right after the start to one after the event.
TEST(FrameBound, UnitWaitCountsFromItsStart) {
  for (uint32_t n = 0; n <= kUnitDone + 2; ++n) {
    std::string src = "        out   io[1]\n";
    for (uint32_t i = 0; i < n; ++i) src += "        nop\n";
    src += "        wait  4\nend:    nop\n";
    const auto p = asm_of(src);
    const uint64_t hand = 2 + n + std::max<uint64_t>(1, kUnitDone > n ? kUnitDone - n : 0);
    EXPECT_EQ(unit_bound(p), hand) << n << " nops";
    EXPECT_EQ(unit_model(p), hand) << n << " nops";
  }
}

// Which start counts and which paths: the latest start on each path back
// (a start 20 nops earlier does not shorten the wait after a second one);
// two paths from the start (j.eq skips 10 nops), the wait charged by the
// shorter (the j.eq's clock: 14) on the longer path: 2 + 1 + 1 + 10 + 14
// = 28, above the model's 18 on either path; a callee that starts: the
// start may be its last instruction, so the wait counts from the return
// (call 2, out nop ret 3, wait 15 = 20; the model: 18); an `out` indexed
// by x may write any address, so it counts as a start (15, the model 1).
TEST(FrameBound, UnitWaitTakesTheLatestStartOnEveryPath) {
  std::string twice = "        out   io[1]\n";
  for (int i = 0; i < 20; ++i) twice += "        nop\n";
  twice += "        out   io[1]\n        wait  4\nend:    nop\n";
  const auto p = asm_of(twice);
  EXPECT_EQ(unit_bound(p), 2u + 20u + 1u + kUnitDone);
  EXPECT_EQ(unit_model(p), 2u + 20u + 1u + kUnitDone);

  std::string branch = "        ld    io[0]\n        out   io[1]\n        j.eq  skip\n";
  for (int i = 0; i < 10; ++i) branch += "        nop\n";
  branch += "skip:   wait  4\nend:    nop\n";
  const auto q = asm_of(branch);
  EXPECT_EQ(unit_bound(q), 28u);
  EXPECT_EQ(unit_model(q, {0}), 18u);  // j.eq taken: 14 B clocks of wait
  EXPECT_EQ(unit_model(q, {1}), 18u);  // through the nops: 4
  EXPECT_LE(unit_model(q, {1}), unit_bound(q));

  const auto r = asm_of(
      "        call  st\n"
      "        wait  4\n"
      "end:    nop\n"
      "st:     out   io[1]\n"
      "        nop\n"
      "        ret\n");
  EXPECT_EQ(unit_bound(r), 20u);
  EXPECT_EQ(unit_model(r), 18u);

  std::string indexed = "        out   io[1]\n";
  for (int i = 0; i < 20; ++i) indexed += "        nop\n";
  indexed += "        out   io[5 + x1]\n        wait  4\nend:    nop\n";
  const auto s = asm_of(indexed);
  EXPECT_EQ(unit_bound(s), 2u + 20u + 1u + kUnitDone);
  EXPECT_EQ(unit_model(s), 2u + 20u + 1u + 1u);
}

// The shared counter of a loop with two back edges on one register (the
// taxel loop's shape): 5 djnz x3 in all, whichever way each pass goes.
// Passes: from pa through j.eq (taken) to pb's djnz: nop 1, ld io 1, j.eq
// 2, djnz 1 = 5, or on to pa's djnz: 1 + 1 + 2 + 1 + 1 = 6; 5 passes x 6
// = 30, ldx 2: 32 (entered at pa).
TEST(FrameBound, LoopWithTwoBackEdgesOnOneCounter) {
  const auto p = asm_of(
      "        ldx   x3, 5\n"
      "pa:     nop\n"
      "        ld    io[0]\n"
      "        j.eq  pb\n"
      "        nop\n"
      "        djnz  x3, pa\n"
      "        j     end\n"
      "pb:     djnz  x3, pa\n"
      "end:    nop\n");
  EXPECT_EQ(bound_to_end(p), 32u + 1u);  // + the j end of the last pass (or none after pb)
  QueueIo io;
  io.reads = {1, 1, 1, 1, 1};
  EXPECT_EQ(model_to_end(p, io), 33u);
}

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

// A loop nothing bounds, a djnz whose count is not a constant, a wait with
// no latency: errors naming the file, line, address and instruction.
TEST(FrameBound, UnboundedLoopsAreErrorsNamingTheLine) {
  const auto p = asm_of(
      "        nop\n"
      "loop:   ld    io[0]\n"
      "        j.ne  loop\n"
      "end:    nop\n");
  EXPECT_EQ(error_of([&] { bound_to_end(p); }),
            "prog.fe:3: unbounded loop: this branch closes a loop that no djnz with a constant "
            "count and no .bound bounds (address 2: j.ne  loop)");
  const auto q = asm_of(
      "        ld    io[0]\n"
      "        tax   x3\n"
      "loop:   nop\n"
      "        djnz  x3, loop\n"
      "end:    nop\n");
  EXPECT_EQ(error_of([&] { bound_to_end(q); }),
            "prog.fe:4: djnz: x3 is not loaded with a constant (ldx) on every path into its "
            "loop (from address 1): give the loop a .bound (address 3: djnz  x3, loop)");
  const auto r = asm_of(
      "        ldx   x3, 4\n"
      "loop:   addx  x3, 1\n"
      "        djnz  x3, loop\n"
      "end:    nop\n");
  EXPECT_NE(error_of([&] { bound_to_end(r); }).find("prog.fe:3: djnz: x3 changes in its loop"),
            std::string::npos);
  const auto w = asm_of(
      "        wait  8\n"
      "end:    nop\n");
  EXPECT_EQ(error_of([&] { bound_to_end(w); }),
            "prog.fe:1: wait: no bound is known for its events (mask 8) (address 0: wait  8)");
  const auto b = asm_of(
      "        .bound 3\n"
      "        add   1\n"
      "end:    nop\n");
  EXPECT_NE(error_of([&] { bound_to_end(b); }).find("prog.fe:2: .bound: expected a branch"),
            std::string::npos);
}

// The directive: a count >= 0, an instruction after it, one at a time.
TEST(FrameBound, BoundDirective) {
  const auto p = asm_of(
      "loop:   nop\n"
      "        .bound 2 * 3 + 1\n"
      "        j     loop\n"
      "end:\n");
  ASSERT_EQ(p.bounds.size(), 1u);
  EXPECT_EQ(p.bounds.at(1).count, 7);
  EXPECT_EQ(p.bounds.at(1).per, -1);
  EXPECT_EQ(error_of([] { asm_of("        .bound -1\n        nop\n"); }),
            "prog.fe:1: .bound: expected a count >= 0, got -1");
  EXPECT_EQ(error_of([] { asm_of("        nop\n        .bound 1\n"); }),
            "prog.fe:2: .bound: expected an instruction after it");
  EXPECT_EQ(error_of([] { asm_of("        .bound 1\n        .bound 2\n        nop\n"); }),
            "prog.fe:2: .bound: the .bound of line 1 has no instruction yet");
}

// The DTMF microprogram for the default scene's plan and every variant of
// its assembly (.if: no ghost filter, no neurons, the neuron unit, its
// lanes, the barrel shifter): every loop of a frame and of a command is
// bounded (no error), and the figures are printed.
TEST(FrameBound, DtmfDefaultPlan) {
  const eskin::sim::Scene sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto spec = eskin::sim::dtmf_top_spec(sc, kDtmfTopClkHz);
  for (int v = 0; v < 5; ++v) {
    auto s = spec;
    if (v == 0) s.ghost = false;
    if (v == 1) s.spikes = false;
    if (v == 2) s.neuron_unit = true;
    if (v == 3) s.neuron_unit = true, s.neuron_lanes = 5;
    if (v == 4) s.engine_fast_shift = true;
    const DtmfFrameBound b = dtmf_frame_bound(make_dtmf_top_plan(s));
    std::printf("variant %d: frame %llu, command %llu\n", v, (unsigned long long)b.frame,
                (unsigned long long)b.command);
    EXPECT_GT(b.frame, 0u);
  }
  const auto plan = make_dtmf_top_plan(spec);
  const DtmfFrameBound b = dtmf_frame_bound(plan);
  std::printf("default plan: frame %llu, command %llu, total %llu clocks; any neuron "
              "constants and command frames: %llu + %llu\n",
              (unsigned long long)b.frame, (unsigned long long)b.command,
              (unsigned long long)b.total(), (unsigned long long)b.frame_any,
              (unsigned long long)b.command_any);
  EXPECT_GT(b.frame, 0u);
  EXPECT_GT(b.command, 0u);
}

}  // namespace
