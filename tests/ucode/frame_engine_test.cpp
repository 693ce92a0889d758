// ucode/frame_engine.h (the instruction-set model) and ucode/frame_engine_asm.h
// (assembler, disassembler) against expectations written here from the ISA
// manual (docs/frame_engine.md) in plain 64/128-bit integer arithmetic.
// Every check is exact: the ISA defines each result bit and each clock.
#include "ucode/frame_engine.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "ucode/frame_engine_asm.h"

namespace {

using eskin::hls::FrameEngine;
namespace fe = eskin::hls::fe;
namespace fa = eskin::hls::fe_asm;
using i128 = __int128;

// A 48-bit two's complement value of any integer (the wrap of A).
int64_t w48(i128 v) {
  const i128 m = i128(1) << 48;
  i128 r = v % m;
  if (r < 0) r += m;
  if (r >= m / 2) r -= m;
  return int64_t(r);
}
// floor(a / 2^n) for any n >= 0.
i128 floor_div_pow2(i128 a, int n) {
  const i128 d = i128(1) << n;
  i128 q = a / d;
  if (a % d != 0 && a < 0) q -= 1;
  return q;
}
// The field table of the manual, each entry from its definition:
// bits lo..hi of w as a number, signed or not.
int64_t bits(uint32_t w, int lo, int hi, bool is_signed) {
  int64_t v = 0;
  for (int b = hi; b >= lo; --b) v = v * 2 + ((w >> b) & 1u);
  const int64_t width = hi - lo + 1;
  if (is_signed && ((w >> hi) & 1u)) v -= int64_t(1) << width;
  return v;
}
int64_t expect_field(uint32_t w, uint32_t f) {
  switch (f) {
    case 0: return bits(w, 0, 31, true);
    case 1: return bits(w, 0, 31, false);
    case 2: return bits(w, 0, 15, true);
    case 3: return bits(w, 0, 15, false);
    case 4: return bits(w, 16, 31, true);
    case 5: return bits(w, 0, 14, false);
    case 6: return bits(w, 15, 31, true);
    default: return bits(w, 0, 7, false);
  }
}

// IO that answers reads from a table and records writes with their clocks.
struct TableIo {
  std::map<uint16_t, uint32_t> table;
  struct Read { uint16_t addr; uint64_t clock; };
  struct Write { uint16_t addr; uint32_t data; uint64_t clock; };
  std::vector<Read> reads;
  std::vector<Write> writes;
  std::function<uint16_t(uint64_t)> ev = [](uint64_t) { return uint16_t(0); };
  uint32_t io_read(uint16_t a, uint64_t c) {
    reads.push_back({a, c});
    return table.count(a) ? table[a] : 0u;
  }
  void io_write(uint16_t a, uint32_t d, uint64_t c) { writes.push_back({a, d, c}); }
  uint16_t events(uint64_t c) { return ev(c); }
};

struct Small {
  static constexpr int IW = 6, DW = 5, KW = 3;
  static constexpr bool FAST_SHIFT = false;
};
struct Fast : eskin::hls::FrameEngineConfig {  // the barrel shifter
  static constexpr bool FAST_SHIFT = true;
};
using Engine = FrameEngine<>;

// Engine with one instruction (or a program) at 0.
template <class CFG = eskin::hls::FrameEngineConfig>
std::unique_ptr<FrameEngine<CFG>> with(std::vector<uint32_t> prog) {
  auto e = std::make_unique<FrameEngine<CFG>>();
  e->load_program(prog.data(), uint32_t(prog.size()));
  e->reset();
  return e;
}

constexpr int64_t kMax47 = (int64_t(1) << 47) - 1;
constexpr int64_t kMin47 = -(int64_t(1) << 47);

// ---------------------------------------------------------------------------
// Data instructions: A op m for every operand source.

TEST(FrameEngineModel, AluOpsOnEveryFieldOfDmemWords) {
  std::mt19937_64 rng(1);
  const int64_t a_edges[] = {0, 1, -1, kMax47, kMin47, 0x7FFFFFFF, -0x80000000ll};
  TableIo io;
  for (int it = 0; it < 4000; ++it) {
    const uint32_t fn = uint32_t(rng() % 8), f = uint32_t(rng() % 8);
    const uint32_t word = it % 5 == 0 ? uint32_t(0x80000000u >> (rng() % 32)) ^ uint32_t(rng() % 3)
                                      : uint32_t(rng());
    const int64_t a0 = it % 7 == 0 ? a_edges[rng() % 7] : w48(i128(int64_t(rng())));
    auto e = with({fe::mem(fn, fe::kDmem, 0, f, 9)});
    e->set_dmem(9, word);
    e->set_a(a0);
    // min and max compare in one B clock and write in the next.
    ASSERT_EQ(e->step(io), fn == fe::kMin || fn == fe::kMax ? 3u : 2u);
    const int64_t m = expect_field(word, f);
    int64_t want = 0;
    switch (fn) {
      case 0: want = m; break;
      case 1: want = w48(i128(a0) + m); break;
      case 2: want = w48(i128(a0) - m); break;
      case 3: want = a0 < m ? a0 : m; break;
      case 4: want = a0 > m ? a0 : m; break;
      // Bitwise on the 48-bit patterns of A and m.
      case 5: want = w48(i128(a0 & m)); break;
      case 6: want = w48(i128(a0 | m)); break;
      default: want = w48(i128(a0 ^ m)); break;
    }
    ASSERT_EQ(e->a(), want) << "fn " << fn << " field " << f << " word " << std::hex << word
                            << " A " << std::dec << a0;
  }
}

TEST(FrameEngineModel, OperandSourcesKromIoAccPImmediate) {
  TableIo io;
  io.table[0x1234] = 0xFFFF8001u;
  // KROM with index: ea = 3 + X1 wraps into KW bits (KW = 8: 256 words).
  {
    auto e = with({fe::ctl(fe::kLdx, 1, 0, 258), fe::mem(fe::kAdd, fe::kKrom, 1, fe::kLu, 3)});
    const uint32_t k[6] = {0, 0, 0, 0, 0, 0xABCD1234u};  // word 5 = (258 + 3) mod 256
    e->load_krom(k, 6);
    e->set_a(10);
    e->step(io);
    e->step(io);
    EXPECT_EQ(e->a(), 10 + 0x1234);
  }
  // IO: the read happens in cycle A (clock 0), sign-extended low half.
  {
    auto e = with({fe::mem(fe::kLd, fe::kIo, 0, fe::kL, 0x1234)});
    io.reads.clear();
    e->step(io);
    EXPECT_EQ(e->a(), -32767);
    ASSERT_EQ(io.reads.size(), 1u);
    EXPECT_EQ(io.reads[0].addr, 0x1234);
    EXPECT_EQ(io.reads[0].clock, 0u);
  }
  // A's own low word through a field (space a): .h of A[31:0].
  {
    auto e = with({fe::mem(fe::kLd, fe::kAcc, 0, fe::kH, 0)});
    e->set_a(int64_t(0x5A5A80017777ll));
    e->step(io);
    EXPECT_EQ(e->a(), int64_t(int16_t(0x8001)));
  }
  // P: fields of P (.h15 is P >> 15, floor).
  {
    auto e = with({fe::imm(fe::kLt, -300), fe::imm(fe::kMpy, 20000), fe::preg(fe::kLd, fe::kH15),
                   fe::preg(fe::kAdd, fe::kW)});
    for (int i = 0; i < 4; ++i) e->step(io);
    const int64_t p = -300 * 20000;
    EXPECT_EQ(e->p(), p);
    EXPECT_EQ(e->a(), int64_t(floor_div_pow2(p, 15)) + p);
  }
  // Immediate: sign-extended 26 bits.
  {
    auto e = with({fe::imm(fe::kLd, -(1 << 25)), fe::imm(fe::kSub, (1 << 25) - 1)});
    e->step(io);
    EXPECT_EQ(e->a(), -(int64_t(1) << 25));
    e->step(io);
    EXPECT_EQ(e->a(), -(int64_t(1) << 26) + 1);
  }
}

TEST(FrameEngineModel, AddWrapsAt48Bits) {
  TableIo io;
  auto e = with({fe::imm(fe::kAdd, 1), fe::imm(fe::kSub, 1)});
  e->set_a(kMax47);
  e->step(io);
  EXPECT_EQ(e->a(), kMin47);
  e->step(io);
  EXPECT_EQ(e->a(), kMax47);
}

TEST(FrameEngineModel, LtMpyTakeTheLow16BitsSigned) {
  TableIo io;
  const int32_t vals[] = {-32768, -32767, -1, 0, 1, 32767};
  for (int32_t tv : vals)
    for (int32_t mv : vals) {
      // The operands come as 32-bit words with junk above bit 15.
      auto e = with({fe::mem(fe::kLt, fe::kDmem, 0, fe::kW, 1), fe::mem(fe::kMpy, fe::kDmem, 0, fe::kW, 2)});
      e->set_dmem(1, (uint32_t(tv) & 0xFFFFu) | 0x12340000u);
      e->set_dmem(2, (uint32_t(mv) & 0xFFFFu) | 0xFEDC0000u);
      // lt: cycle A and B (the first instruction after reset); mpy: its
      // cycle A runs in lt's B clock, so one more.
      EXPECT_EQ(e->step(io) + e->step(io), 3u);
      EXPECT_EQ(e->t(), tv);
      EXPECT_EQ(e->p(), int64_t(tv) * mv) << tv << " * " << mv;
    }
}

// ---------------------------------------------------------------------------
// Shifts: value and clocks.

struct ShiftCase { uint32_t fn; int64_t a; uint32_t n; };

int64_t expect_shift(uint32_t fn, int64_t a, uint32_t n) {
  if (fn == fe::kShl) return w48(i128(a) * (i128(1) << n));
  if (fn == fe::kShr) return int64_t(floor_div_pow2(a, int(n)));
  if (n == 0) return a;
  return int64_t(floor_div_pow2(i128(a) + (i128(1) << (n - 1)), int(n)));
}
// Clocks from the manual's table: immediate counts start shifting in the
// first B clock; other operands load the count first; rnd adds one clock.
// One bit per clock, or all n bits in one clock with the barrel shifter.
uint32_t expect_shift_clocks(uint32_t fn, uint32_t n, bool imm, bool fast) {
  if (n == 0) return 2;
  return (imm ? 1 : 2) + (fast ? 1 : n) + (fn == fe::kRnd ? 1 : 0);
}

template <class CFG>
void shifts_at_the_edges_and_random() {
  std::mt19937_64 rng(2);
  std::vector<ShiftCase> cases;
  const int64_t edges[] = {0, 1, -1, 2, -2, 3, -3, kMax47, kMin47, kMin47 + 1, 0x123456789ABll};
  for (uint32_t fn : {fe::kShl, fe::kShr, fe::kRnd})
    for (int64_t a : edges)
      for (uint32_t n : {0u, 1u, 2u, 15u, 46u, 47u, 48u, 49u, 62u, 63u}) cases.push_back({fn, a, n});
  for (int i = 0; i < 3000; ++i)
    cases.push_back({fe::kShl + uint32_t(rng() % 3), w48(i128(int64_t(rng()))), uint32_t(rng() % 64)});
  TableIo io;
  for (const auto& c : cases) {
    // Immediate count, and the same count from DMEM (high bits ignored).
    auto e = with<CFG>({fe::imm(c.fn, int32_t(c.n)), fe::mem(c.fn, fe::kDmem, 0, fe::kW, 4)});
    e->set_dmem(4, c.n | 0xFFFFFFC0u);
    e->set_a(c.a);
    const uint32_t clk = e->step(io);
    ASSERT_EQ(e->a(), expect_shift(c.fn, c.a, c.n)) << "fn " << c.fn << " a " << c.a << " n " << c.n;
    ASSERT_EQ(clk, expect_shift_clocks(c.fn, c.n, true, CFG::FAST_SHIFT));
    e->set_a(c.a);
    // Its cycle A runs in the last B clock of the shift before (which ends
    // in a clock known in advance: an immediate count), so one clock less.
    ASSERT_EQ(e->step(io), expect_shift_clocks(c.fn, c.n, false, CFG::FAST_SHIFT) - 1);
    ASSERT_EQ(e->a(), expect_shift(c.fn, c.a, c.n));
  }
}

TEST(FrameEngineModel, ShiftsAtTheEdgesAndRandom) {
  shifts_at_the_edges_and_random<eskin::hls::FrameEngineConfig>();
}

// The barrel shifter: the same results; `shl 15` in 2 clocks instead of 16,
// `rnd 12` in 3 instead of 14, `rnd [m]` in 4.
TEST(FrameEngineModel, FastShiftSameResultsInOneClock) {
  shifts_at_the_edges_and_random<Fast>();
}

// ---------------------------------------------------------------------------
// Square roots: r = floor(sqrt(A)) iff r^2 <= A < (r+1)^2; q = the nearest
// integer iff (2q-1)^2 < 4A < (2q+1)^2 (no ties: 4A is never an odd square).

// Clocks: 1 + 50 root steps + 1 (two clocks a digit), 1 + 13 + 1 with the
// barrel shifter (two digits a clock; 26 digits, the first a leading 0).
template <class E>
void check_roots(E& e, int64_t a) {
  const uint32_t clocks = E::FAST_SHIFT ? 15u : 52u;
  TableIo io;
  e.set_pc(0);
  e.set_a(a);
  ASSERT_EQ(e.step(io), clocks);
  const i128 r = e.a();
  e.set_a(a);
  ASSERT_EQ(e.step(io), clocks);
  const i128 q = e.a();
  if (a < 0) {
    ASSERT_EQ(r, 0);
    ASSERT_EQ(q, 0);
    return;
  }
  ASSERT_TRUE(r >= 0 && r * r <= a && (r + 1) * (r + 1) > a) << "sqrt " << a << " -> " << int64_t(r);
  ASSERT_TRUE(q >= 0 && 4 * i128(a) < (2 * q + 1) * (2 * q + 1) &&
              (q == 0 || (2 * q - 1) * (2 * q - 1) < 4 * i128(a)))
      << "sqrtr " << a << " -> " << int64_t(q);
}

template <class CFG>
void sqrt_exhaustive_small_and_random() {
  auto e = with<CFG>({fe::ctl(fe::kSqrt, 0, 0, 0), fe::ctl(fe::kSqrtr, 0, 0, 0)});
  for (int64_t a = 0; a < (1 << 16); ++a) check_roots(*e, a);
  std::mt19937_64 rng(3);
  for (int i = 0; i < 20000; ++i) check_roots(*e, int64_t(rng() >> 17));  // 0 .. 2^47 - 1
  for (int64_t k : {int64_t(1) << 23, (int64_t(1) << 23) + 1, int64_t(11863282)  /* (k+1)^2 < 2^47 */}) {
    for (int64_t d : {-1, 0, 1}) check_roots(*e, k * k + d);
    check_roots(*e, k * k + k);      // just below k + 1/2: rounds down
    check_roots(*e, k * k + k + 1);  // just above: rounds up
  }
  for (int64_t a : {kMax47, int64_t(-1), kMin47}) check_roots(*e, a);
}

TEST(FrameEngineModel, SqrtExhaustiveSmallAndRandom48Bit) {
  sqrt_exhaustive_small_and_random<eskin::hls::FrameEngineConfig>();
}

// The barrel shifter's root: the same roots, a digit a clock.
TEST(FrameEngineModel, FastShiftSqrtSameRootsInHalfTheClocks) {
  sqrt_exhaustive_small_and_random<Fast>();
}

// ---------------------------------------------------------------------------
// Control flow.

TEST(FrameEngineModel, JumpConditions) {
  const int64_t as[] = {kMin47, -5, -1, 0, 1, 5, kMax47};
  const char* names[8] = {"always", "eq", "lt", "le", "never", "ne", "ge", "gt"};
  TableIo io;
  for (uint32_t cond = 0; cond < 8; ++cond)
    for (int64_t a : as) {
      const bool want[8] = {true, a == 0, a < 0, a <= 0, false, a != 0, a >= 0, a > 0};
      auto e = with({fe::ctl(fe::kJ, 0, cond, 40)});
      e->set_a(a);
      EXPECT_EQ(e->step(io), 2u);
      EXPECT_EQ(e->pc(), want[cond] ? 40u : 1u) << names[cond] << " A=" << a;
    }
}

TEST(FrameEngineModel, DjnzCountsDownAndFallsThroughAtZero) {
  // 0: ldx x2, 3   1: add 1   2: djnz x2, 1   3: ...
  auto e = with({fe::ctl(fe::kLdx, 2, 0, 3), fe::imm(fe::kAdd, 1), fe::ctl(fe::kDjnz, 2, 0, 1)});
  TableIo io;
  uint64_t clocks = 0;
  while (e->pc() != 3) clocks += e->step(io);
  EXPECT_EQ(e->a(), 3);
  EXPECT_EQ(e->x(2), 0);
  // ldx 2 (cycle A after reset); then every add and djnz 1: each cycle A
  // runs in the B clock before (djnz decides from X, not A).
  EXPECT_EQ(clocks, 2u + 3 + 3);
  // djnz x0 decrements nothing and always jumps (X0 - 1 = 0xFFFF != 0).
  auto f = with({fe::ctl(fe::kDjnz, 0, 0, 9)});
  f->step(io);
  EXPECT_EQ(f->pc(), 9u);
}

TEST(FrameEngineModel, CallRetTwoDeepStack) {
  // 0: call 10   1: nop
  // 10: call 20  11: ret
  // 20: call 30  21: ret
  // 30: ret
  std::vector<uint32_t> prog(32, fe::ctl(fe::kNopCtl, 0, 0, 0));
  prog[0] = fe::ctl(fe::kCall, 0, 0, 10);
  prog[10] = fe::ctl(fe::kCall, 0, 0, 20);
  prog[11] = fe::ctl(fe::kRet, 0, 0, 0);
  prog[20] = fe::ctl(fe::kCall, 0, 0, 30);
  prog[21] = fe::ctl(fe::kRet, 0, 0, 0);
  prog[30] = fe::ctl(fe::kRet, 0, 0, 0);
  auto e = with(prog);
  TableIo io;
  std::vector<uint32_t> pcs;
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(e->step(io), i == 0 ? 2u : 1u);  // calls and returns overlap
    pcs.push_back(e->pc());
  }
  // Three calls deep: the return address 1 fell off the two-entry stack;
  // returns go 30 -> 21 -> 11, then 11 again and again (the bottom entry
  // stays when popped).
  EXPECT_EQ(pcs, (std::vector<uint32_t>{10, 20, 30, 21, 11, 11, 11}));
  // ... which the model records: one overflow, the call at 20 (cycle A in
  // clock 2: the calls overlap), as rtl/frame_engine.v counts it.
  EXPECT_EQ(e->stack_overflows(), 1u);
  EXPECT_EQ(e->stack_overflow_pc(), 20u);
  EXPECT_EQ(e->stack_overflow_clock(), 2u);
  e->reset();
  EXPECT_EQ(e->stack_overflows(), 0u);
  EXPECT_EQ(e->stack_depth(), 0u);
}

// Only a call with both entries live overflows: two deep, twice, after a
// return with none live (which leaves none live, not fewer).
TEST(FrameEngineModel, CallsTwoDeepAfterAnEmptyReturnDoNotOverflow) {
  // 5: ret (to 0, none live)   0: call 10  1: call 10  2: j 2
  // 10: call 20  11: ret   20: ret
  std::vector<uint32_t> prog(32, fe::ctl(fe::kNopCtl, 0, 0, 0));
  prog[0] = prog[1] = fe::ctl(fe::kCall, 0, 0, 10);
  prog[2] = fe::ctl(fe::kJ, 0, 0, 2);
  prog[5] = prog[11] = prog[20] = fe::ctl(fe::kRet, 0, 0, 0);
  prog[10] = fe::ctl(fe::kCall, 0, 0, 20);
  auto e = with(prog);
  e->set_pc(5);
  TableIo io;
  std::vector<uint32_t> pcs, depths;
  for (int i = 0; i < 9; ++i) {
    e->step(io);
    pcs.push_back(e->pc());
    depths.push_back(e->stack_depth());
  }
  EXPECT_EQ(pcs, (std::vector<uint32_t>{0, 10, 20, 11, 1, 10, 20, 11, 2}));
  EXPECT_EQ(depths, (std::vector<uint32_t>{0, 1, 2, 1, 0, 1, 2, 1, 0}));
  EXPECT_EQ(e->stack_overflows(), 0u);
}

TEST(FrameEngineModel, WaitCountsClocksUntilTheMaskedEvent) {
  TableIo io;
  // Event bit 2 rises at clock 7: the wait (cycle A at clock 2) ends at the
  // end of clock 7, i.e. takes 1 + 5 clocks (B clocks 3..7).
  io.ev = [](uint64_t c) { return uint16_t(c >= 7 ? 0x0004 : 0x0001); };
  auto e = with({fe::imm(fe::kLd, 1), fe::ctl(fe::kWait, 0, 0, 0x0006), fe::imm(fe::kLd, 2)});
  EXPECT_EQ(e->step(io), 2u);
  EXPECT_EQ(e->step(io), 6u);
  EXPECT_EQ(e->clocks(), 8u);
  // With a clock limit the wait stops early and resumes.
  auto f = with({fe::ctl(fe::kWait, 0, 0, 0x0004)});
  EXPECT_EQ(f->step(io, 4), 4u);
  EXPECT_TRUE(f->in_wait());
  EXPECT_EQ(f->pc(), 1u);
  EXPECT_EQ(f->step(io), 4u);  // clocks 4..7
  EXPECT_FALSE(f->in_wait());
  EXPECT_EQ(f->clocks(), 8u);
}

TEST(FrameEngineModel, IndexRegisterOps) {
  TableIo io;
  auto e = with({fe::ctl(fe::kLdx, 1, 0, 0xFFFE), fe::ctl(fe::kAddx, 1, 0, 5), fe::ctl(fe::kTax, 3, 0, 0),
                 fe::ctl(fe::kTxa, 1, 0, 0), fe::ctl(fe::kLdx, 0, 0, 7), fe::ctl(fe::kTxa, 0, 0, 0)});
  e->set_a(-2);  // tax takes A[15:0]
  // tax reads A in its cycle A; addx before it leaves A alone, so it
  // overlaps addx's B (OverlapAndItsBubbles has the cases that wait).
  for (uint32_t want : {2u, 1u, 1u, 1u}) EXPECT_EQ(e->step(io), want);
  EXPECT_EQ(e->x(1), 3);       // 0xFFFE + 5 wraps
  EXPECT_EQ(e->x(3), 0xFFFE);
  EXPECT_EQ(e->a(), 3);        // txa: zero-extended X1
  e->step(io);
  e->step(io);
  EXPECT_EQ(e->a(), 0);        // X0 is always 0
}

TEST(FrameEngineModel, StoreAndOutWriteA31to0) {
  TableIo io;
  auto e = with({fe::ctl(fe::kLdx, 2, 0, 40), fe::mem(fe::kSt, fe::kDmem, 2, 0, 0xFFFF),
                 fe::mem(fe::kOut, fe::kIo, 2, 0, 2)});
  e->set_a(-(int64_t(1) << 40) + 0x12345678);
  e->step(io);
  e->step(io);
  EXPECT_TRUE(e->last().stored);
  EXPECT_EQ(e->last().st_addr, 39u);  // 40 + 0xFFFF = 39 (mod 2^16)
  EXPECT_EQ(e->dmem(39), 0x12345678u);
  e->step(io);
  ASSERT_EQ(io.writes.size(), 1u);
  EXPECT_EQ(io.writes[0].addr, 42);
  EXPECT_EQ(io.writes[0].data, 0x12345678u);
  // ldx: A 0, B 1; st: A 1, B 2; out: A 2, B 3 (each A in the B before).
  EXPECT_EQ(io.writes[0].clock, 3u);
}

// The overlap (docs/frame_engine.md, "Timing"): cycle A runs in the last B
// clock of the instruction before, except where that would read A in the
// clock the instruction before writes it, DMEM in the clock `st` writes it, IO in the clock `out`
// writes it, or follow a B whose last clock is known only in that clock.
// Each case: the clocks of every instruction, first after reset (A + B).
TEST(FrameEngineModel, OverlapAndItsBubbles) {
  struct Case {
    const char* what;
    std::vector<uint32_t> prog;
    std::vector<uint32_t> clocks;
  };
  const uint32_t ld1 = fe::imm(fe::kLd, 1), ld2 = fe::imm(fe::kLd, 2);
  const uint32_t st5 = fe::mem(fe::kSt, fe::kDmem, 0, 0, 5);
  const uint32_t out3 = fe::mem(fe::kOut, fe::kIo, 0, 0, 3);
  const uint32_t jne = fe::ctl(fe::kJ, 0, fe::kNe, 0), sqrt = fe::ctl(fe::kSqrt, 0, 0, 0);
  const Case cases[] = {
      {"two loads", {ld1, ld2}, {2, 1}},
      {"DMEM read after st", {ld1, st5, fe::mem(fe::kLd, fe::kDmem, 0, 0, 5)}, {2, 1, 2}},
      {"KROM read after st", {ld1, st5, fe::mem(fe::kLd, fe::kKrom, 0, 0, 5)}, {2, 1, 1}},
      {"IO read after st", {ld1, st5, fe::mem(fe::kLd, fe::kIo, 0, 0, 5)}, {2, 1, 1}},
      {"IO read after out", {ld1, out3, fe::mem(fe::kLd, fe::kIo, 0, 0, 4)}, {2, 1, 2}},
      {"DMEM read after out", {ld1, out3, fe::mem(fe::kLd, fe::kDmem, 0, 0, 4)}, {2, 1, 1}},
      {"st after st", {ld1, st5, st5}, {2, 1, 1}},
      {"jump always", {ld1, fe::ctl(fe::kJ, 0, fe::kAlways, 0)}, {2, 1}},
      {"jump never", {ld1, fe::ctl(fe::kJ, 0, fe::kNever, 0)}, {2, 1}},
      {"jump on A", {ld1, fe::ctl(fe::kJ, 0, fe::kNe, 0)}, {2, 2}},
      {"tax", {ld1, fe::ctl(fe::kTax, 1, 0, 0)}, {2, 2}},
      // A read of A after an instruction that leaves A alone: no bubble.
      {"jump on A after st", {ld1, st5, jne}, {2, 1, 1}},
      {"jump on A after out", {ld1, out3, fe::ctl(fe::kJ, 0, fe::kEq, 0)}, {2, 1, 1}},
      {"jump on A after lt", {ld1, fe::imm(fe::kLt, 3), jne}, {2, 1, 1}},
      {"jump on A after mpy", {ld1, fe::imm(fe::kMpy, 3), jne}, {2, 1, 1}},
      {"tax after addx", {ld1, fe::ctl(fe::kAddx, 1, 0, 1), fe::ctl(fe::kTax, 2, 0, 0)}, {2, 1, 1}},
      {"sqrt after ldx", {ld1, fe::ctl(fe::kLdx, 1, 0, 1), sqrt}, {2, 1, fe::kSqrtClocks - 1}},
      {"jump on A after shl by an immediate 0", {fe::imm(fe::kShl, 0), jne}, {2, 1}},
      // ... and after one that writes it: a bubble.
      {"jump on A after shl by an immediate 1", {fe::imm(fe::kShl, 1), jne}, {2, 2}},
      {"jump on A after txa", {fe::ctl(fe::kTxa, 1, 0, 0), jne}, {2, 2}},
      {"jump on A after min", {ld1, fe::imm(fe::kMin, 0), jne}, {2, 2, 2}},
      {"tax after and", {ld1, fe::imm(fe::kAnd, 1), fe::ctl(fe::kTax, 2, 0, 0)}, {2, 1, 2}},
      {"sqrt", {ld1, sqrt, ld2}, {2, fe::kSqrtClocks, 1}},
      {"min, then a load", {ld1, fe::imm(fe::kMin, 0), ld2}, {2, 2, 1}},
      {"after a wait", {fe::ctl(fe::kWait, 0, 0, 1), ld2}, {2, 2}},
      {"after shl by an immediate 0", {fe::imm(fe::kShl, 0), ld2}, {2, 1}},
      {"after shl by a DMEM 0", {fe::mem(fe::kShl, fe::kDmem, 0, 0, 9), ld2}, {2, 2}},
      {"after shl by a DMEM 2", {fe::mem(fe::kShl, fe::kDmem, 0, 0, 10), ld2}, {4, 1}},
  };
  for (const auto& c : cases) {
    TableIo io;
    io.ev = [](uint64_t) { return uint16_t(1); };
    auto e = with(c.prog);
    e->set_dmem(9, 0);
    e->set_dmem(10, 2);
    std::vector<uint32_t> got;
    for (size_t i = 0; i < c.clocks.size(); ++i) got.push_back(e->step(io));
    EXPECT_EQ(got, c.clocks) << c.what;
  }
}

TEST(FrameEngineModel, UnusedFunctionCodesDoNothingInTwoClocks) {
  TableIo io;
  const uint32_t words[] = {fe::mem(15, 0, 1, 3, 7), fe::imm(fe::kSt, 5), fe::imm(fe::kOut, 5),
                            fe::imm(15, 5), fe::preg(fe::kSt, 0), fe::preg(fe::kOut, 0),
                            fe::ctl(11, 1, 2, 3), fe::ctl(12, 0, 0, 0), fe::ctl(15, 3, 7, 0xFFFF)};
  for (uint32_t w : words) {
    auto e = with({w});
    e->set_a(77);
    e->set_x(1, 5);
    EXPECT_EQ(e->step(io), 2u);
    EXPECT_EQ(e->a(), 77);
    EXPECT_EQ(e->x(1), 5);
    EXPECT_EQ(e->pc(), 1u);
    EXPECT_FALSE(e->last().stored);
  }
  EXPECT_TRUE(io.writes.empty());
}

TEST(FrameEngineModel, ResetClearsRegistersNotDmem) {
  TableIo io;
  auto e = with({fe::imm(fe::kLd, 9), fe::mem(fe::kSt, 0, 0, 0, 3), fe::imm(fe::kLt, 3), fe::imm(fe::kMpy, 3),
                 fe::ctl(fe::kLdx, 1, 0, 4), fe::ctl(fe::kCall, 0, 0, 0)});
  for (int i = 0; i < 6; ++i) e->step(io);
  e->reset();
  EXPECT_EQ(e->a(), 0);
  EXPECT_EQ(e->p(), 0);
  EXPECT_EQ(e->t(), 0);
  EXPECT_EQ(e->x(1), 0);
  EXPECT_EQ(e->pc(), 0u);
  EXPECT_EQ(e->stack(0), 0u);
  EXPECT_EQ(e->clocks(), 0u);
  EXPECT_EQ(e->dmem(3), 9u);
}

TEST(FrameEngineModel, SmallConfigWrapsAddresses) {
  // IW = 6, DW = 5, KW = 3: PC, DMEM and KROM addresses wrap at their sizes.
  auto e = std::make_unique<FrameEngine<Small>>();
  const uint32_t prog[] = {fe::imm(fe::kLd, 5), fe::mem(fe::kSt, 0, 0, 0, 33)};
  e->load_program(prog, 2);
  const uint32_t k[8] = {0, 0, 0, 0, 0, 0, 0, 0x77};
  e->load_krom(k, 8);
  e->reset();
  TableIo io;
  e->step(io);
  e->step(io);
  EXPECT_EQ(e->dmem(1), 5u);
  e->set_pc(63);
  EXPECT_EQ(e->pc(), 63u);
  const uint32_t j[] = {fe::mem(fe::kLd, fe::kKrom, 0, 0, 15)};
  e->load_program(j, 1, 63);
  e->step(io);
  EXPECT_EQ(e->pc(), 0u);
  EXPECT_EQ(e->a(), 0x77);
}

// ---------------------------------------------------------------------------
// Assembler: every form, against words packed by hand from the manual's
// encoding table ([31:30] class, [29:26] fn, [25:24] space, [23:22] x,
// [21:19] field/cond, [15:0] addr; imm26 at [25:0]).

uint32_t asm1(const std::string& line, const fa::Options& opt = {}) {
  const auto p = fa::assemble(line + "\n", "t.fe", opt);
  EXPECT_EQ(p.words.size(), 1u) << line;
  return p.words.empty() ? 0 : p.words[0];
}

TEST(FrameEngineAsm, EveryForm) {
  const std::pair<const char*, uint32_t> cases[] = {
      {"ld.h [0x10 + x1]", 0x00600010}, {"add k[5]", 0x05000005},
      {"ld io[3]", 0x02000003},         {"out io[7 + x2]", 0x3A800007},
      {"lt.h15 a", 0x23300000},         {"lta.h15", 0x23300000},
      {"add p", 0x84000000},            {"apac", 0x84000000},
      {"ld.h15 p", 0x80300000},         {"lpac", 0x80000000},
      {"spac 0", 0x88000000},           {"ld -1", 0x43FFFFFF},
      {"ldi -1", 0x43FFFFFF},           {"addi 33554431", 0x45FFFFFF},
      {"shl 12", 0x6800000C},           {"rnd k[2]", 0x31000002},
      {"rndm k[2]", 0x31000002},        {"shr.b [x3]", 0x2CF80000},
      {"st [100 + x3]", 0x34C00064},    {"st [x1 - 1]", 0x3440FFFF},
      {"j.lt 5", 0xC0100005},           {"j 7", 0xC0000007},
      {"j.nv 1", 0xC0200001},           {"j.gt 2", 0xC0380002},
      {"djnz x2, 3", 0xC4800003},       {"call 9", 0xC8000009},
      {"ret", 0xCC000000},              {"wait 0x8001", 0xD0008001},
      {"sqrt", 0xD4000000},             {"sqrtr", 0xD8000000},
      {"ldx x1, 0x1234", 0xDC401234},   {"addx x3, -1", 0xE0C0FFFF},
      {"tax x2", 0xE4800000},           {"txa x1", 0xE8400000},
      {"nop", 0xEC000000},              {"mpy.l k[4 + x1]", 0x25500004},
      {"xor.wu [1]", 0x1C080001},       {"min.lu io[2]", 0x0E180002},
  };
  for (const auto& [text, word] : cases) EXPECT_EQ(asm1(text), word) << text;
}

TEST(FrameEngineAsm, LabelsEquOrgExpressionsAndPredefinedSymbols) {
  fa::Options opt;
  opt.symbols["PORT"] = 0x20;
  const std::string src =
      "; a comment line\n"
      "        .equ  N, 3 * (2 + 1)        ; 9\n"
      "        .equ  M, N << 2 | 1 & 3     ; (9 << 2) | (1 & 3) = 37\n"
      "start:  ld    M - N                 ; 28\n"
      "loop:   out   io[PORT + x1]\n"
      "        j     loop\n"
      "        .org  0x10\n"
      "far:    j     start                 ; forward and backward labels\n"
      "        .word 0xDEADBEEF, -1, .     ; . is this address (0x13)\n"
      "        j     far + ~0 + 1\n";
  const auto p = fa::assemble(src, "t.fe", opt);
  ASSERT_EQ(p.words.size(), 0x15u);
  EXPECT_EQ(p.words[0], 0x4000001Cu);
  EXPECT_EQ(p.words[1], 0x3A400020u);
  EXPECT_EQ(p.words[2], 0xC0000001u);
  EXPECT_EQ(p.words[3], 0u);  // the gap
  EXPECT_EQ(p.words[0x10], 0xC0000000u);
  EXPECT_EQ(p.words[0x11], 0xDEADBEEFu);
  EXPECT_EQ(p.words[0x12], 0xFFFFFFFFu);
  EXPECT_EQ(p.words[0x13], 0x13u);
  EXPECT_EQ(p.words[0x14], 0xC0000010u);
  EXPECT_EQ(p.symbols.at("M"), 37);
  EXPECT_EQ(p.symbols.at("far"), 0x10);
  EXPECT_EQ(p.symbols.at("PORT"), 0x20);
  const std::string lst = fa::listing_text(p);
  EXPECT_NE(lst.find("0001  3a400020      5  loop:   out   io[PORT + x1]"), std::string::npos) << lst;
  EXPECT_NE(lst.find("  far "), std::string::npos);
  EXPECT_EQ(fa::readmemh_text({0x1u, 0xC0000010u}), "00000001\nc0000010\n");
  EXPECT_EQ(fa::parse_readmemh("00000001 // one\nc0000010\n", "k.hex"),
            (std::vector<uint32_t>{1u, 0xC0000010u}));
}

// .if / .else / .endif: a branch not taken emits no word and defines no
// label, nested blocks inside it stay skipped whatever their conditions, and
// the taken branch's labels get the addresses the emitted words leave.
TEST(FrameEngineAsm, ConditionalAssemblyTakesOneBranch) {
  fa::Options opt;
  opt.symbols["UNIT"] = 1;
  const std::string src =
      "        .equ  SLOW, UNIT - 1\n"
      "        .if   UNIT\n"
      "fast:   ld    1\n"
      "        .if   SLOW                  ; inner, not taken\n"
      "        ld    2\n"
      "        .else\n"
      "        ld    3\n"
      "        .endif\n"
      "        .else\n"
      "slow:   ld    4\n"
      "        .if   1                     ; inside a branch not taken\n"
      "        ld    5\n"
      "        .endif\n"
      "        .endif\n"
      "end:    j     end\n";
  const auto p = fa::assemble(src, "t.fe", opt);
  EXPECT_EQ(p.words, (std::vector<uint32_t>{0x40000001u, 0x40000003u, 0xC0000002u}));
  EXPECT_EQ(p.symbols.at("end"), 2);
  EXPECT_EQ(p.symbols.count("slow"), 0u);
  opt.symbols["UNIT"] = 0;
  const auto q = fa::assemble(src, "t.fe", opt);
  EXPECT_EQ(q.words, (std::vector<uint32_t>{0x40000004u, 0x40000005u, 0xC0000002u}));
  EXPECT_EQ(q.symbols.count("fast"), 0u);
  EXPECT_EQ(q.symbols.at("slow"), 0);
}

void expect_error(const std::string& src, const std::string& want, const fa::Options& opt = {}) {
  try {
    fa::assemble(src, "dtmf.fe", opt);
    ADD_FAILURE() << "no error for: " << src;
  } catch (const fa::AsmError& e) {
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos)
        << "got: " << e.what() << "\nwanted: " << want;
  }
}

TEST(FrameEngineAsm, ErrorsNameFileLineAndWhatWasExpected) {
  expect_error("nop\nld.x [1]\n",
               "dtmf.fe:2: ld: field: expected one of .w .wu .l .lu .h .l15 .h15 .b, got .x");
  expect_error("nop\nnop\nfrob 3\n", "dtmf.fe:3: unknown instruction 'frob'");
  expect_error("ld [NOPE]\n", "dtmf.fe:1: ld: address: undefined symbol 'NOPE'");
  expect_error("ld 33554432\n", "dtmf.fe:1: ld: immediate: expected -33554432..33554431, got 33554432");
  expect_error("shl 64\n", "dtmf.fe:1: shl: shift count: expected 0..63, got 64");
  expect_error("lt 65536\n", "dtmf.fe:1: lt: 16-bit immediate: expected -32768..65535, got 65536");
  expect_error("j 4096\n", "dtmf.fe:1: j: target: expected 0..4095, got 4096");
  expect_error("ld [65536]\n", "dtmf.fe:1: ld: address: expected -32768..65535, got 65536");
  expect_error("st k[1]\n", "dtmf.fe:1: st: expected a DMEM operand");
  expect_error("out [1]\n", "dtmf.fe:1: out: expected an IO operand");
  expect_error("ld.h 5\n", "dtmf.fe:1: ld: expected no field with an immediate, got .h");
  expect_error("j.zz 1\n", "dtmf.fe:1: j: condition: expected one of .eq .ne .lt .ge .gt .le .nv, got .zz");
  expect_error("djnz x4, 1\n", "dtmf.fe:1: djnz: expected an index register x0..x3, got 'x4'");
  expect_error("djnz x1\n", "dtmf.fe:1: djnz: expected 2 operands, got 1");
  expect_error("wait 0\n", "dtmf.fe:1: wait: event mask: expected 1..65535, got 0");
  expect_error("a: nop\n", "dtmf.fe:1: label 'a': a register name cannot be a label");
  expect_error("l: nop\nl: nop\n", "dtmf.fe:2: label 'l': already defined");
  expect_error(".equ Q, LATER\nLATER: nop\n", "dtmf.fe:1: .equ: undefined symbol 'LATER'");
  expect_error(".org 5000\n", "dtmf.fe:1: .org: expected an IMEM address 0..4095, got 5000");
  expect_error(".org 1\nnop\n.org 1\nnop\n", "dtmf.fe:4: address 1 already holds the word of line 2");
  expect_error("ld [3 - x1]\n", "dtmf.fe:1: ld: address: the index register must be added");
  expect_error("ld (1 + 2\n", "dtmf.fe:1: ld: immediate: expected ')'");
  expect_error("ld 1 +\n", "dtmf.fe:1: ld: immediate: expected a value, got the end of the expression");
  expect_error("ld 0x\n", "dtmf.fe:1: ld: immediate: expected digits after the number prefix");
  expect_error("apac 15\n", "dtmf.fe:1: apac: P shift: expected 0");
  expect_error(".bss 3\n", "dtmf.fe:1: directive: expected .equ, .org, .word, .bound, .if, .else, .endif, "
                           ".macro, .endm or .include, got .bss");
  expect_error("nop\n.if 1\nnop\n", "dtmf.fe:2: .if: no .endif before the end of the file");
  expect_error(".if 1\n.endif\n.else\n", "dtmf.fe:3: .else: no .if before it");
  expect_error(".endif\n", "dtmf.fe:1: .endif: no .if before it");
  expect_error(".if 0\n.else\n.else\n.endif\n",
               "dtmf.fe:3: .else: a second .else for the .if of line 1");
  expect_error(".if\n.endif\n", "dtmf.fe:1: .if: expected an expression");
  expect_error(".if 1\n.endif 2\n", "dtmf.fe:2: .endif: expected nothing after it, got '2'");
  expect_error(".if LATER\n.endif\nLATER: nop\n", "dtmf.fe:1: .if: undefined symbol 'LATER'");
  expect_error(".if 0\nonly: nop\n.endif\nj only\n", "dtmf.fe:4: j: target: undefined symbol 'only'");
  expect_error("ld x1\n", "dtmf.fe:1: ld: immediate: 'x1' is a register, expected a value");
  fa::Options small;
  small.imem_words = 2;
  expect_error("nop\nnop\nnop\n", "dtmf.fe:3: program: address 2 is beyond the IMEM (2 words)", small);
  EXPECT_THROW(fa::parse_readmemh("0000000g\n", "k.hex"), fa::AsmError);
  EXPECT_THROW(fa::assemble_file("/nonexistent/x.fe"), fa::AsmError);
}

// Disassembly of every canonical form assembles back to the same word; a
// word the assembler cannot make shows as .word with its meaning.
TEST(FrameEngineAsm, DisassemblerRoundTrip) {
  std::mt19937 rng(4);
  auto round_trip = [](uint32_t w) {
    const std::string text = fa::disassemble(w);
    EXPECT_EQ(asm1(text), w) << std::hex << w << ": " << text;
    return text;
  };
  for (int i = 0; i < 20000; ++i) {
    const uint32_t fn = rng() % 15, space = rng() % 4, x = rng() % 4, f = rng() % 8,
                   addr = rng() & 0xFFFF;
    if (fn == fe::kSt) round_trip(fe::mem(fn, fe::kDmem, x, 0, addr));
    else if (fn == fe::kOut) round_trip(fe::mem(fn, fe::kIo, x, 0, addr));
    else if (space == fe::kAcc) round_trip(fe::mem(fn, space, 0, f, 0));
    else round_trip(fe::mem(fn, space, x, f, addr));
    if (fn <= fe::kRnd) {
      const bool sh = fn >= fe::kShl;
      const bool narrow = fn == fe::kLt || fn == fe::kMpy;
      const int32_t v = sh ? int32_t(rng() % 64) : narrow ? int32_t(rng() % 98304) - 32768
                                                          : int32_t(rng() << 6) >> 6;
      round_trip(fe::imm(fn, v));
      round_trip(fe::preg(fn, f));
    }
    const uint32_t target = rng() % 4096;
    round_trip(fe::ctl(fe::kJ, 0, rng() % 8, target));
    round_trip(fe::ctl(fe::kDjnz, x, 0, target));
    round_trip(fe::ctl(fe::kLdx + rng() % 2, x, 0, addr));
    round_trip(fe::ctl(fe::kTax + rng() % 2, x, 0, 0));
  }
  EXPECT_EQ(round_trip(fe::ctl(fe::kWait, 0, 0, 0x30)), "wait 0x30");
  EXPECT_EQ(round_trip(fe::mem(fe::kLd, fe::kKrom, 2, fe::kH15, 12)), "ld.h15 k[12 + x2]");
  EXPECT_EQ(round_trip(fe::preg(fe::kSub, fe::kW)), "sub p");
  // Non-canonical words: bits the hardware ignores, or operands out of the
  // assembler's range.
  EXPECT_EQ(fa::disassemble(fe::mem(fe::kLd, 0, 0, 0, 5) | (1u << 16)), ".word 0x00010005 ; ld [5]");
  EXPECT_EQ(fa::disassemble(fe::imm(fe::kShl, 64)), ".word 0x68000040 ; shl 64");
  EXPECT_EQ(fa::disassemble(fe::mem(fe::kSt, fe::kKrom, 0, 0, 1)), ".word 0x35000001 ; st k[1]");
  EXPECT_EQ(fa::disassemble(fe::ctl(13, 0, 0, 0)), ".word 0xf4000000 ; nop");
  for (int i = 0; i < 20000; ++i) {
    const uint32_t w = rng();
    const std::string t = fa::disassemble(w);
    if (t.rfind(".word", 0) != 0) EXPECT_EQ(asm1(t), w) << t;
    else EXPECT_EQ(asm1(t.substr(0, t.find(';'))), w) << t;
  }
}

// The model runs assembled text: a small loop with every clock accounted.
TEST(FrameEngineAsm, AssembledProgramRunsOnTheModel) {
  const auto p = fa::assemble(
      "        ldx  x1, 4\n"
      "        ld   0\n"
      "loop:   add  k[x1 + 0]\n"
      "        djnz x1, loop\n"
      "        st   [7]\n"
      "halt:   j    halt\n",
      "sum.fe");
  auto e = std::make_unique<Engine>();
  e->load_program(p.words.data(), uint32_t(p.words.size()));
  const uint32_t k[5] = {100, 1, 2, 3, 4};
  e->load_krom(k, 5);
  e->reset();
  TableIo io;
  const uint64_t halt = uint64_t(p.symbols.at("halt"));
  e->run(io, 1000, [&](const Engine& en) { return en.pc() == halt; });
  EXPECT_EQ(e->dmem(7), 4u + 3 + 2 + 1);
  // ldx 2 clocks (after reset), then ld, 4 x (add, djnz) and st one each.
  EXPECT_EQ(e->clocks(), 2u + 1 + 4 * 2 + 1);
}

}  // namespace
