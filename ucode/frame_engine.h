// frame_engine: instruction-set model of the microcoded arithmetic unit
// (rtl/frame_engine.v). Bit-exact and clock-exact: every instruction changes
// the registers, DMEM and the IO bus exactly as the RTL does, and takes the
// same number of clocks. docs/frame_engine.md is the ISA manual.
//
// Number formats: A is a signed 48-bit accumulator (kept here sign-extended
// in an int64_t); arithmetic wraps modulo 2^48. P is the signed 32-bit
// product of two signed 16-bit operands (exact, never overflows). T and
// X1..X3 are 16 bits. Memory words are 32 bits.
//
// Configuration (CONFIG_T, a struct of constants like FrameEngineConfig):
//   IW  IMEM address bits (program of 2^IW words)       4..12
//   DW  DMEM address bits (2^DW words, not initialised) 4..15
//   KW  KROM address bits (2^KW constant words)         1..12
// The IO bus belongs to the caller: step()/run() take an IO object with
//   uint32_t io_read(uint16_t addr, uint64_t clock);   // `space io` read
//   void io_write(uint16_t addr, uint32_t data, uint64_t clock);  // `out`
//   uint16_t events(uint64_t clock);                   // sampled by `wait`
// `clock` is the index of the clock (0 = the first clock after reset) in
// which the RTL drives the bus: io_re and io_raddr in cycle A of the reading
// instruction (the data is used in the clock after), io_we and io_waddr in its cycle B,
// and events in each clock of a `wait`'s cycle B (the wait ends at the end of
// the first clock whose events match its mask).
//
// Overlap (docs/frame_engine.md, "Timing"): an instruction's cycle A runs in
// the last B clock of the one before, unless that would break the order of
// a shared resource, so most instructions cost their B clocks only. Cycle A
// waits one clock (a bubble) when it reads A (a jump on A, tax, sqrt,
// sqrtr) right after an instruction that writes A (A is still being
// written; after st, out, lt, mpy, a shift by an immediate 0 or a control
// instruction other than txa, sqrt and sqrtr it is final), reads DMEM
// right after `st` (one DMEM port) or reads IO right after `out` (the
// write lands at the same edge), and it never overlaps a `wait` or a
// shift whose count operand is 0 (their last clock is known only in that
// clock).
#pragma once

#include <cstdint>

#include "hls/isqrt.h"

namespace eskin::hls {

// ---- encoding ----------------------------------------------------------------
// [31:30] class  [29:26] fn  then, by class:
//   mem  [25:24] space [23:22] x [21:19] field [15:0] addr
//   imm  [25:0] signed immediate
//   P    [21:19] field (operand: the field of P)
//   ctl  [23:22] x [21:19] cond [15:0] target / imm16 / event mask
namespace fe {

enum Class : uint32_t { kMem = 0, kImm = 1, kP = 2, kCtl = 3 };
// Functions of the mem, imm and P classes (the operand m is the class's).
enum Fn : uint32_t {
  kLd = 0, kAdd = 1, kSub = 2, kMin = 3, kMax = 4, kAnd = 5, kOr = 6, kXor = 7,
  kLt = 8, kMpy = 9, kShl = 10, kShr = 11, kRnd = 12, kSt = 13, kOut = 14, kNopFn = 15
};
// Functions of the ctl class (11..15 do nothing).
enum Ctl : uint32_t {
  kJ = 0, kDjnz = 1, kCall = 2, kRet = 3, kWait = 4, kSqrt = 5, kSqrtr = 6,
  kLdx = 7, kAddx = 8, kTax = 9, kTxa = 10, kNopCtl = 11
};
enum Space : uint32_t { kDmem = 0, kKrom = 1, kIo = 2, kAcc = 3 };
enum Field : uint32_t { kW = 0, kWu = 1, kL = 2, kLu = 3, kH = 4, kL15 = 5, kH15 = 6, kB = 7 };
// Jump conditions on A; bit 2 negates.
enum Cond : uint32_t { kAlways = 0, kEq = 1, kLtz = 2, kLe = 3, kNever = 4, kNe = 5, kGe = 6, kGt = 7 };

constexpr uint32_t cls_of(uint32_t w) { return w >> 30; }
constexpr uint32_t fn_of(uint32_t w) { return (w >> 26) & 15u; }
constexpr uint32_t space_of(uint32_t w) { return (w >> 24) & 3u; }
constexpr uint32_t x_of(uint32_t w) { return (w >> 22) & 3u; }
constexpr uint32_t field_of(uint32_t w) { return (w >> 19) & 7u; }
constexpr uint32_t addr_of(uint32_t w) { return w & 0xFFFFu; }
constexpr int32_t imm_of(uint32_t w) {  // sign-extended [25:0]
  return int32_t(w << 6) >> 6;
}

constexpr uint32_t mem(uint32_t fn, uint32_t space, uint32_t x, uint32_t field, uint32_t addr) {
  return (kMem << 30) | ((fn & 15u) << 26) | ((space & 3u) << 24) | ((x & 3u) << 22) |
         ((field & 7u) << 19) | (addr & 0xFFFFu);
}
constexpr uint32_t imm(uint32_t fn, int32_t value) {
  return (kImm << 30) | ((fn & 15u) << 26) | (uint32_t(value) & 0x3FFFFFFu);
}
constexpr uint32_t preg(uint32_t fn, uint32_t field) {
  return (kP << 30) | ((fn & 15u) << 26) | ((field & 7u) << 19);
}
constexpr uint32_t ctl(uint32_t fn, uint32_t x, uint32_t cond, uint32_t addr) {
  return (kCtl << 30) | ((fn & 15u) << 26) | ((x & 3u) << 22) | ((cond & 7u) << 19) |
         (addr & 0xFFFFu);
}

// Clocks per instruction (docs/frame_engine.md, "Timing").
constexpr uint32_t kSqrtClocks = 52;      // 1 + 50 root steps + 1
constexpr uint32_t kSqrtClocksFast = 15;  // FAST_SHIFT: 1 + 13 root steps (2 digits) + 1

// ---- timing: the one definition of the manual's "Timing" -------------------
// FrameEngine below runs by these, and the static frame bound
// (ucode/frame_bound.h) adds them up over the paths of a program, so the
// bound uses the clocks the RTL tests check.

// shl, shr, rnd: the functions whose operand is a shift count n (m[5:0]).
constexpr bool is_shift(uint32_t w) {
  const uint32_t fn = fn_of(w);
  return cls_of(w) != kCtl && (fn == kShl || fn == kShr || fn == kRnd);
}
// What the next instruction's cycle A needs of the one before it.
struct Hazard {
  bool overlap_ok = false;  // cycle A may run in its last B clock (not after
                            // reset, a wait or a shift by a loaded count of 0)
  bool st = false, out = false;
  bool writes_a = false;    // its last B clock may write A
};
// The hazard instruction w leaves; n is its shift count (is_shift), else unused.
constexpr Hazard hazard_after(uint32_t w, uint32_t n) {
  const uint32_t cls = cls_of(w), fn = fn_of(w);
  Hazard h;
  h.st = cls == kMem && fn == kSt;
  h.out = cls == kMem && fn == kOut;
  // Writes A in its B clocks: the arithmetic and logic, the shifts (not an
  // immediate shift by 0), txa and the roots.
  h.writes_a = cls == kCtl ? (fn == kTxa || fn == kSqrt || fn == kSqrtr)
                           : (fn <= kXor || fn == kShl || fn == kShr || fn == kRnd);
  h.overlap_ok = !(cls == kCtl && fn == kWait);
  if (is_shift(w) && n == 0) {
    h.overlap_ok = cls == kImm;  // a loaded count of 0 ends B in the loading clock
    h.writes_a = cls != kImm;    // by an immediate 0: A is left alone
  }
  return h;
}
// Whether w reads A in its cycle A (a jump on a condition, tax, the roots).
constexpr bool reads_a_in_cycle_a(uint32_t w) {
  const uint32_t fn = fn_of(w);
  return cls_of(w) == kCtl &&
         ((fn == kJ && (field_of(w) & 3u) != 0) || fn == kTax || fn == kSqrt || fn == kSqrtr);
}
// Whether w's cycle A runs in the last B clock of the instruction that
// left `prev` (else it costs a clock of its own: a bubble).
constexpr bool overlaps(const Hazard& prev, uint32_t w) {
  const uint32_t fn = fn_of(w);
  const bool reads = cls_of(w) == kMem && fn <= kRnd;
  return prev.overlap_ok && !(reads_a_in_cycle_a(w) && prev.writes_a) &&
         !(prev.st && reads && space_of(w) == kDmem) && !(prev.out && reads && space_of(w) == kIo);
}
// B clocks of w, any instruction but `wait` (its B clocks are the events');
// n is its shift count (is_shift), `fast` the barrel shifter.
constexpr uint32_t b_clocks(uint32_t w, uint32_t n, bool fast) {
  const uint32_t cls = cls_of(w), fn = fn_of(w);
  if (cls == kCtl)
    return fn == kSqrt || fn == kSqrtr ? (fast ? kSqrtClocksFast : kSqrtClocks) - 1 : 1;
  if (fn == kMin || fn == kMax) return 2;  // compare, then write
  if (is_shift(w)) {
    if (n == 0) return 1;
    // An immediate count is known in cycle A, another takes a B clock to
    // load; rnd adds a clock for the rounding carry.
    return (cls == kImm ? 0 : 1) + (fast ? 1 : n) + (fn == kRnd ? 1 : 0);
  }
  return 1;
}

}  // namespace fe

struct FrameEngineConfig {
  static constexpr int IW = 9;
  static constexpr int DW = 8;
  static constexpr int KW = 8;
  // rtl/frame_engine.v's FAST_SHIFT: shl/shr/rnd by a barrel shifter (one
  // clock for any count) instead of one bit per clock, and sqrt/sqrtr two
  // root digits a clock instead of one every two. Timing only: every result
  // is the same.
  static constexpr bool FAST_SHIFT = false;
};

// An IO bus with nothing on it: reads give 0, writes vanish, no events.
struct FrameEngineNullIo {
  uint32_t io_read(uint16_t, uint64_t) { return 0; }
  void io_write(uint16_t, uint32_t, uint64_t) {}
  uint16_t events(uint64_t) { return 0; }
};

// Side effects of the instruction step() just finished (for traces and tests).
struct FrameEngineRetired {
  uint32_t pc = 0;          // its address
  uint32_t word = 0;        // its encoding
  uint32_t clocks = 0;      // clocks it took (from the previous one's last clock)
  uint64_t a_clock = 0;     // the clock of its cycle A
  bool stored = false;      // `st`: DMEM[st_addr] = st_data
  uint32_t st_addr = 0;
  uint32_t st_data = 0;
};

template <class CONFIG_T = FrameEngineConfig>
class FrameEngine {
 public:
  static constexpr int IW = CONFIG_T::IW;
  static constexpr int DW = CONFIG_T::DW;
  static constexpr int KW = CONFIG_T::KW;
  static constexpr bool FAST_SHIFT = CONFIG_T::FAST_SHIFT;
  static_assert(IW >= 4 && IW <= 12, "frame_engine: IW must be 4..12");
  static_assert(DW >= 4 && DW <= 15, "frame_engine: DW must be 4..15");
  static_assert(KW >= 1 && KW <= 12, "frame_engine: KW must be 1..12");
  static constexpr uint32_t kImemWords = 1u << IW;
  static constexpr uint32_t kDmemWords = 1u << DW;
  static constexpr uint32_t kKromWords = 1u << KW;

  // ---- loading -------------------------------------------------------------
  // Words beyond n keep their previous contents; loads beyond the memory end
  // are dropped (the caller checks sizes, e.g. the assembler's .org range).
  void load_program(const uint32_t* words, uint32_t n, uint32_t at = 0) {
    for (uint32_t i = 0; i < n && at + i < kImemWords; ++i) imem_[at + i] = words[i];
  }
  void load_krom(const uint32_t* words, uint32_t n, uint32_t at = 0) {
    for (uint32_t i = 0; i < n && at + i < kKromWords; ++i) krom_[at + i] = words[i];
  }
  uint32_t dmem(uint32_t addr) const { return dmem_[addr & (kDmemWords - 1)]; }
  void set_dmem(uint32_t addr, uint32_t value) { dmem_[addr & (kDmemWords - 1)] = value; }
  uint32_t imem(uint32_t addr) const { return imem_[addr & (kImemWords - 1)]; }
  uint32_t krom(uint32_t addr) const { return krom_[addr & (kKromWords - 1)]; }

  // Reset: every register 0, PC 0, the clock count 0. DMEM is left alone
  // (the RTL's DMEM is not initialised: programs clear what they use).
  void reset() {
    a_ = 0; p_ = 0; t_ = 0; pc_ = 0; clocks_ = 0;
    for (auto& x : x_) x = 0;
    for (auto& s : stack_) s = 0;
    depth_ = 0;
    overflows_ = 0;
    overflow_pc_ = 0;
    overflow_clock_ = 0;
    waiting_ = false;
    hazard_ = fe::Hazard{};
    last_ = FrameEngineRetired{};
  }

  // ---- state ---------------------------------------------------------------
  int64_t a() const { return a_; }
  int32_t p() const { return p_; }
  int16_t t() const { return t_; }
  uint16_t x(int i) const { return i >= 1 && i <= 3 ? x_[i] : 0; }
  uint32_t pc() const { return pc_; }  // next instruction (during a wait: the one after it)
  uint32_t stack(int i) const { return stack_[i & 1]; }  // 0: top
  // Return stack overflows: calls made while both entries held a live
  // return address (the older one fell off; docs/frame_engine.md, "Return
  // stack"), counted since reset as rtl/frame_engine.v counts them, and the
  // first one's address and cycle-A clock. Execution goes on as the RTL's
  // does; the microcode tests fail on any.
  uint32_t stack_depth() const { return depth_; }
  uint64_t stack_overflows() const { return overflows_; }
  uint32_t stack_overflow_pc() const { return overflow_pc_; }
  uint64_t stack_overflow_clock() const { return overflow_clock_; }
  uint64_t clocks() const { return clocks_; }
  bool in_wait() const { return waiting_; }
  const FrameEngineRetired& last() const { return last_; }
  // Test access to registers (e.g. to start a routine with given inputs).
  void set_a(int64_t v) { a_ = wrap48(v); }
  void set_x(int i, uint16_t v) { if (i >= 1 && i <= 3) x_[i] = v; }
  void set_pc(uint32_t v) { pc_ = v & (kImemWords - 1); }

  // ---- execution -------------------------------------------------------------
  // Runs one instruction (or the rest of a wait in progress) and returns the
  // clocks it took. A wait whose events do not come by the absolute clock
  // count `limit` stops there with in_wait() set; the next step() resumes it.
  template <class IO>
  uint32_t step(IO& io, uint64_t limit = ~uint64_t(0)) {
    const uint64_t start = clocks_;
    if (waiting_) {
      wait_clocks(io, limit);
      last_.clocks += uint32_t(clocks_ - start);
      return uint32_t(clocks_ - start);
    }
    last_ = FrameEngineRetired{};
    last_.pc = pc_;
    last_.word = imem_[pc_];
    const uint32_t clk = execute(io, last_.word, limit);
    last_.clocks = clk;
    return clk;
  }

  // Runs whole instructions until `stop(*this)` holds before one, or until at
  // least `n` clocks have passed (a wait may stop in the middle). Returns the
  // clocks run.
  template <class IO, class Stop>
  uint64_t run(IO& io, uint64_t n, Stop stop) {
    const uint64_t start = clocks_, end = clocks_ + n;
    while (clocks_ < end && !stop(*this)) step(io, end);
    return clocks_ - start;
  }
  template <class IO>
  uint64_t run(IO& io, uint64_t n) {
    return run(io, n, [](const FrameEngine&) { return false; });
  }

  // ---- value helpers (the manual's definitions) ------------------------------
  static int64_t wrap48(int64_t v) {
    return int64_t(uint64_t(v) << 16) >> 16;
  }
  // The 48-bit value of field f of word w.
  static int64_t field(uint32_t w, uint32_t f) {
    switch (f & 7u) {
      case fe::kW: return int32_t(w);
      case fe::kWu: return int64_t(w);
      case fe::kL: return int16_t(w & 0xFFFFu);
      case fe::kLu: return int64_t(w & 0xFFFFu);
      case fe::kH: return int16_t(w >> 16);
      case fe::kL15: return int64_t(w & 0x7FFFu);
      case fe::kH15: return int32_t(w) >> 15;
      default: return int64_t(w & 0xFFu);
    }
  }

 private:
  template <class IO>
  uint32_t execute(IO& io, uint32_t w, uint64_t limit) {
    const uint32_t cls = fe::cls_of(w), fn = fe::fn_of(w), xi = fe::x_of(w);
    const uint32_t addr = fe::addr_of(w);
    const uint64_t start = clocks_;
    const uint64_t c0 = fe::overlaps(hazard_, w) ? clocks_ - 1 : clocks_;  // cycle A
    last_.a_clock = c0;
    uint32_t n = 0;  // a shift's count
    const uint32_t pc1 = (pc_ + 1) & (kImemWords - 1);
    pc_ = pc1;  // end of cycle A; control flow may change it
    if (cls == fe::kCtl && fn == fe::kWait) {
      wait_mask_ = uint16_t(addr);
      waiting_ = true;
      hazard_ = fe::hazard_after(w, 0);
      clocks_ = c0 + 1;
      wait_clocks(io, limit);
      return uint32_t(clocks_ - start);
    } else if (cls == fe::kCtl) {
      if (fn == fe::kCall && depth_ == 2 && overflows_++ == 0)
        overflow_pc_ = last_.pc, overflow_clock_ = c0;
      control(fn, xi, fe::field_of(w), addr, pc1);
    } else {
      const uint16_t ea = uint16_t(addr + xreg(xi));
      const bool imm_class = cls == fe::kImm;
      // The operand m (read in cycle A, used in the first clock of B).
      int64_t m = 0;
      if (fn <= fe::kRnd) {
        if (imm_class) {
          m = fe::imm_of(w);
        } else {
          uint32_t word = uint32_t(p_);
          if (cls == fe::kMem) {
            switch (fe::space_of(w)) {
              case fe::kDmem: word = dmem_[ea & (kDmemWords - 1)]; break;
              case fe::kKrom: word = krom_[ea & (kKromWords - 1)]; break;
              case fe::kIo: word = io.io_read(ea, c0); break;
              default: word = uint32_t(uint64_t(a_)); break;
            }
          }
          m = field(word, fe::field_of(w));
        }
      }
      switch (fn) {
        case fe::kLd: a_ = m; break;
        case fe::kAdd: a_ = wrap48(a_ + m); break;
        case fe::kSub: a_ = wrap48(a_ - m); break;
        case fe::kMin:  // compare, then write: one more B clock (fe::b_clocks)
          if (a_ >= m) a_ = m;
          break;
        case fe::kMax:
          if (a_ < m) a_ = m;
          break;
        case fe::kAnd: a_ = wrap48(a_ & m); break;
        case fe::kOr: a_ = wrap48(a_ | m); break;
        case fe::kXor: a_ = wrap48(a_ ^ m); break;
        case fe::kLt: t_ = int16_t(uint16_t(m)); break;
        case fe::kMpy: p_ = int32_t(t_) * int32_t(int16_t(uint16_t(m))); break;
        case fe::kShl: case fe::kShr: case fe::kRnd:
          n = uint32_t(m) & 63u;
          shift(fn, n);
          break;
        case fe::kSt:
          if (cls == fe::kMem) {
            dmem_[ea & (kDmemWords - 1)] = uint32_t(uint64_t(a_));
            last_.stored = true;
            last_.st_addr = ea & (kDmemWords - 1);
            last_.st_data = uint32_t(uint64_t(a_));
          }
          break;
        case fe::kOut:
          if (cls == fe::kMem) io.io_write(ea, uint32_t(uint64_t(a_)), c0 + 1);
          break;
        default: break;
      }
    }
    hazard_ = fe::hazard_after(w, n);
    clocks_ = c0 + 1 + fe::b_clocks(w, n, FAST_SHIFT);  // cycle A and the B clocks
    return uint32_t(clocks_ - start);
  }

  // shl/shr/rnd by n (its clocks: fe::b_clocks; n = 0 leaves A alone).
  void shift(uint32_t fn, uint32_t n) {
    if (n == 0) return;
    if (fn == fe::kShl) {
      a_ = n >= 48 ? 0 : wrap48(int64_t(uint64_t(a_) << n));
      return;
    }
    const int64_t q = a_ >> (n >= 48 ? 47 : n);             // floor(A / 2^n)
    if (fn == fe::kShr) {
      a_ = q;
      return;
    }
    const int64_t half = n - 1 >= 47 ? (a_ < 0) : ((a_ >> (n - 1)) & 1);  // bit n-1 of A
    a_ = q + half;
  }

  void control(uint32_t fn, uint32_t xi, uint32_t cond, uint32_t addr, uint32_t pc1) {
    const uint32_t target = addr & (kImemWords - 1);
    switch (fn) {
      case fe::kJ: {
        const bool base = (cond & 3u) == 0 ? true
                          : (cond & 3u) == 1 ? a_ == 0
                          : (cond & 3u) == 2 ? a_ < 0
                                             : a_ <= 0;
        if (base != bool(cond & 4u)) pc_ = target;
        return;
      }
      case fe::kDjnz: {
        const uint16_t dec = uint16_t(xreg(xi) - 1u);
        if (xi != 0) x_[xi] = dec;
        if (dec != 0) pc_ = target;
        return;
      }
      case fe::kCall:  // push; the older entry of two falls off
        if (depth_ < 2) ++depth_;
        stack_[1] = stack_[0];
        stack_[0] = pc1;
        pc_ = target;
        return;
      case fe::kRet:  // pop; the bottom entry stays
        if (depth_ > 0) --depth_;
        pc_ = stack_[0];
        stack_[0] = stack_[1];
        return;
      case fe::kSqrt: case fe::kSqrtr:
        // sqrtr: floor(sqrt(A) + 1/2) = (floor(sqrt(4 A)) + 1) >> 1.
        a_ = a_ < 0 ? 0
                    : int64_t(fn == fe::kSqrt ? isqrt64(uint64_t(a_)) : (isqrt64(uint64_t(a_) * 4) + 1) >> 1);
        return;
      case fe::kLdx: if (xi != 0) x_[xi] = uint16_t(addr); return;
      case fe::kAddx: if (xi != 0) x_[xi] = uint16_t(addr + x_[xi]); return;
      case fe::kTax: if (xi != 0) x_[xi] = uint16_t(uint64_t(a_)); return;
      case fe::kTxa: a_ = xreg(xi); return;
      default: return;
    }
  }

  template <class IO>
  void wait_clocks(IO& io, uint64_t limit) {
    while (clocks_ < limit) {
      const uint16_t ev = io.events(clocks_);
      ++clocks_;
      if (ev & wait_mask_) {
        waiting_ = false;
        return;
      }
    }
  }

  uint16_t xreg(uint32_t i) const { return i == 0 ? 0 : x_[i]; }

  uint32_t imem_[kImemWords] = {};
  uint32_t krom_[kKromWords] = {};
  uint32_t dmem_[kDmemWords] = {};
  int64_t a_ = 0;
  int32_t p_ = 0;
  int16_t t_ = 0;
  uint16_t x_[4] = {};
  uint32_t stack_[2] = {};  // return stack, [0] on top
  uint32_t depth_ = 0;      // its live entries (0..2)
  uint64_t overflows_ = 0;
  uint32_t overflow_pc_ = 0;
  uint64_t overflow_clock_ = 0;
  uint32_t pc_ = 0;
  uint64_t clocks_ = 0;
  bool waiting_ = false;
  uint16_t wait_mask_ = 0;
  // What the last instruction leaves the next one's cycle A (fe::overlaps).
  fe::Hazard hazard_;
  FrameEngineRetired last_;
};

}  // namespace eskin::hls
