// rtl/frame_engine.v against its instruction-set model ucode/frame_engine.h,
// instruction for instruction and clock for clock.
//
// Bound: exact. Both run the same program from reset with the same KROM,
// DMEM cleared, the same IO answers and the same events; after every
// instruction the RTL must have taken exactly the model's clocks and hold
// the model's A, P, T, have run its cycle A in the model's clock (the
// overlap: often the last clock of the instruction before) and held the
// model's PC, X1..X3 and return stack after it, and have made the same
// DMEM write and IO writes (address, data, clock). IO reads are answered
// from a table of the address, one clock after io_re (the registered answer
// the manual allows); in every other clock io_rdata carries junk, so a core
// that used it outside the first clock of B would differ. Events are random
// in every clock.
//
// Parameter sets: tests/rtl/frame_engine_tb.v's defaults (IW 9, DW 8: EBR
// DMEM, KW 4 with a KROM_INIT pattern) and frame_engine_test.cmake's
// Vframe_engine_tb_dw14 (IW 10, DW 14: the SPRAM DMEM, KW 8, IMEM from
// $readmemh of the self-test program), and Vframe_engine_tb_fast (IW 10,
// DW 8, KW 4 with the barrel shifter, FAST_SHIFT 1: the model's
// FAST_SHIFT timing, shl/shr in one B clock and rnd in two).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "Vframe_engine_tb.h"
#include "Vframe_engine_tb_dw14.h"
#include "Vframe_engine_tb_fast.h"
#include "clocked_dut.h"
#include "ucode/frame_engine.h"
#include "ucode/frame_engine_asm.h"

namespace {

namespace fe = eskin::hls::fe;
namespace fa = eskin::hls::fe_asm;
using eskin::hls::FrameEngine;

struct SetEbr {  // frame_engine_tb.v defaults
  static constexpr int IW = 9, DW = 8, KW = 4;
  static constexpr bool FAST_SHIFT = false;
};
struct SetSpram {  // Vframe_engine_tb_dw14
  static constexpr int IW = 10, DW = 14, KW = 8;
  static constexpr bool FAST_SHIFT = false;
};
struct SetFast {  // Vframe_engine_tb_fast: the barrel shifter
  static constexpr int IW = 10, DW = 8, KW = 4;
  static constexpr bool FAST_SHIFT = true;
};
// KROM_INIT of frame_engine_tb.v: word k = 0x9e3779b9 (k + 1) mod 2^32.
const uint32_t kKromInit[16] = {0x9e3779b9u, 0x3c6ef372u, 0xdaa66d2bu, 0x78dde6e4u,
                                0x1715609du, 0xb54cda56u, 0x5384540fu, 0xf1bbcdc8u,
                                0x8ff34781u, 0x2e2ac13au, 0xcc623af3u, 0x6a99b4acu,
                                0x08d12e65u, 0xa708a81eu, 0x454021d7u, 0xe3779b90u};

uint64_t mix(uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
uint32_t io_value(uint16_t addr) { return uint32_t(mix(addr + 0x1000)); }
// Each event bit is set with probability 1/8 in each clock.
uint16_t event_value(uint64_t seed, uint64_t clock) {
  const uint64_t r = mix(seed * 0x100000001ull + clock);
  return uint16_t(r & (r >> 16) & (r >> 32));
}

struct IoWrite {
  uint16_t addr;
  uint32_t data;
  uint64_t clock;
  bool operator==(const IoWrite& o) const { return addr == o.addr && data == o.data && clock == o.clock; }
};

struct ModelIo {
  uint64_t seed = 0;
  std::vector<IoWrite> writes;
  uint32_t io_read(uint16_t addr, uint64_t) { return io_value(addr); }
  void io_write(uint16_t addr, uint32_t data, uint64_t clock) { writes.push_back({addr, data, clock}); }
  uint16_t events(uint64_t clock) { return event_value(seed, clock); }
};

// The Verilated core and the model, run in lockstep.
template <class V, class CFG>
class Lockstep {
 public:
  explicit Lockstep(uint64_t seed) : model_(std::make_unique<FrameEngine<CFG>>()) {
    io_.seed = seed;
    dut_.m.clk = 0;
    dut_.m.rst = 1;
    dut_.m.bd_we = 0;
    dut_.m.eval();
  }

  // Back-door loads, with the core held in reset.
  void poke(int mem, uint32_t addr, uint32_t data) {
    dut_.m.rst = 1;
    dut_.m.bd_we = 1;
    dut_.m.bd_mem = uint8_t(mem);
    dut_.m.bd_addr = uint16_t(addr);
    dut_.m.bd_data = data;
    dut_.tick();
    dut_.m.bd_we = 0;
  }
  uint32_t peek(int mem, uint32_t addr) {
    dut_.m.bd_mem = uint8_t(mem);
    dut_.m.bd_addr = uint16_t(addr);
    dut_.m.eval();
    return dut_.m.bd_rdata;
  }
  void load_program(const std::vector<uint32_t>& words) {
    for (uint32_t i = 0; i < words.size(); ++i) poke(0, i, words[i]);
    model_->load_program(words.data(), uint32_t(words.size()));
  }
  void load_krom(const std::vector<uint32_t>& words) {
    for (uint32_t i = 0; i < words.size(); ++i) poke(1, i, words[i]);
    model_->load_krom(words.data(), uint32_t(words.size()));
  }
  void clear_dmem() {
    for (uint32_t i = 0; i < FrameEngine<CFG>::kDmemWords; ++i) {
      poke(2, i, 0);
      model_->set_dmem(i, 0);
    }
  }
  // Two reset clocks (the manual's minimum), then clock 0.
  void reset() {
    dut_.m.rst = 1;
    dut_.m.events = 0;
    dut_.tick();
    dut_.tick();
    dut_.m.rst = 0;
    model_->reset();
    clock_ = 0;
    read_pending_ = false;
    a_done_.clear();
  }
  FrameEngine<CFG>& model() { return *model_; }
  V& rtl() { return dut_.m; }

  // One instruction on both; false (with a gtest failure) on any difference.
  bool step() {
    io_.writes.clear();
    const uint32_t pc0 = model_->pc();
    const uint32_t want_clocks = model_->step(io_);
    const auto& last = model_->last();
    std::vector<IoWrite> rtl_writes;
    bool stored = false;
    uint32_t st_addr = 0, st_data = 0;
    uint32_t n = 0;
    for (;;) {
      V& m = dut_.m;
      m.io_rdata = read_pending_ ? io_value(read_addr_) : ~uint32_t(mix(clock_));
      m.events = event_value(io_.seed, clock_);
      m.eval();
      read_pending_ = m.io_re;
      read_addr_ = m.io_raddr;
      if (m.io_we) rtl_writes.push_back({m.io_waddr, m.io_wdata, clock_});
      if (m.dm_we) {
        stored = true;
        st_addr = m.dm_addr & (FrameEngine<CFG>::kDmemWords - 1);
        st_data = m.dm_data;
      }
      const bool retire = m.retire, a_go = m.a_go;
      dut_.tick();
      if (a_go) a_done_.push_back({clock_, m.pc, m.x1, m.x2, m.x3, m.stk0, m.stk1, m.stk_overflows});
      ++clock_;
      ++n;
      if (retire) break;
      if (n > want_clocks + 64) break;
    }
    V& m = dut_.m;
    const std::string at = "instruction at " + std::to_string(pc0) + " (" + fa::disassemble(last.word) +
                           "), clock " + std::to_string(clock_);
    EXPECT_EQ(n, want_clocks) << at;
    EXPECT_EQ(clock_, model_->clocks()) << at;
    EXPECT_EQ(int64_t(uint64_t(m.acc) << 16) >> 16, model_->a()) << at;
    EXPECT_EQ(int32_t(m.p), model_->p()) << at;
    EXPECT_EQ(int16_t(m.t), model_->t()) << at;
    // Cycle A's effects, seen right after it (the next cycle A may have run
    // since, in this instruction's last clock).
    if (a_done_.empty()) {
      ADD_FAILURE() << at << ": no cycle A";
    } else {
      const ADone a = a_done_.front();
      a_done_.pop_front();
      EXPECT_EQ(a.clock, last.a_clock) << at;
      EXPECT_EQ(a.pc, model_->pc()) << at;
      EXPECT_EQ(a.x1, model_->x(1)) << at;
      EXPECT_EQ(a.x2, model_->x(2)) << at;
      EXPECT_EQ(a.x3, model_->x(3)) << at;
      EXPECT_EQ(a.stk0, model_->stack(0)) << at;
      EXPECT_EQ(a.stk1, model_->stack(1)) << at;
      EXPECT_EQ(a.stk_overflows, model_->stack_overflows()) << at;
    }
    EXPECT_EQ(stored, last.stored) << at;
    if (stored && last.stored) {
      EXPECT_EQ(st_addr, last.st_addr) << at;
      EXPECT_EQ(st_data, last.st_data) << at;
    }
    EXPECT_EQ(rtl_writes, io_.writes) << at;
    return !::testing::Test::HasFailure();
  }

  // Runs until the model's PC is `stop` (at most `limit` instructions, and
  // not past a difference); returns the PC reached.
  uint32_t run_until(uint32_t stop, int limit) {
    for (int i = 0; i < limit && model_->pc() != stop; ++i)
      if (!step()) break;
    return model_->pc();
  }

  // Runs `count` instructions (stops at the first difference); counts the
  // instructions run by class and function code (word bits 31..26).
  void run(int count, std::vector<uint64_t>& by_code) {
    for (int i = 0; i < count; ++i) {
      if (!step()) return;
      ++by_code[model_->last().word >> 26];
    }
  }

  void expect_same_dmem() {
    for (uint32_t i = 0; i < FrameEngine<CFG>::kDmemWords; ++i)
      ASSERT_EQ(peek(2, i), model_->dmem(i)) << "DMEM[" << i << "]";
  }

 private:
  ClockedDut<V> dut_;
  std::unique_ptr<FrameEngine<CFG>> model_;
  ModelIo io_;
  uint64_t clock_ = 0;
  struct ADone {  // the registers cycle A writes, after the edge that ends it
    uint64_t clock;
    uint32_t pc;
    uint16_t x1, x2, x3;
    uint32_t stk0, stk1;
    uint64_t stk_overflows;  // the RTL's count of return stack overflows
  };
  std::deque<ADone> a_done_;
  bool read_pending_ = false;
  uint16_t read_addr_ = 0;
};

// A random program: any 32-bit word (the model defines them all), except
// that a wait's mask is never 0 (it would wait forever on both).
std::vector<uint32_t> random_program(uint32_t words, std::mt19937_64& rng) {
  std::vector<uint32_t> prog(words);
  for (auto& w : prog) {
    w = uint32_t(rng());
    if (fe::cls_of(w) == fe::kCtl && fe::fn_of(w) == fe::kWait && fe::addr_of(w) == 0) w |= 1u;
  }
  return prog;
}

std::vector<uint32_t> random_words(uint32_t n, std::mt19937_64& rng) {
  std::vector<uint32_t> v(n);
  for (auto& w : v) w = uint32_t(rng());
  return v;
}

// Coverage: every one of the 64 class/function codes must have run at least
// 200 times (about 1/64 of the instructions are each code's; loops skew it).
// Random programs nest calls at will, so their return stack overflows:
// the RTL's assertion (built with --assert) is off for them, and its
// overflow count must equal the model's after every cycle A instead.
struct AssertionsOff {
  AssertionsOff() { Verilated::assertOn(false); }
  ~AssertionsOff() { Verilated::assertOn(true); }
};

template <class V, class CFG>
void random_lockstep(uint64_t seed, int programs, int instructions) {
  const AssertionsOff off;
  std::mt19937_64 rng(seed);
  uint64_t overflows = 0;
  std::vector<uint64_t> by_code(64, 0);
  for (int k = 0; k < programs; ++k) {
    Lockstep<V, CFG> ls(seed + uint64_t(k));
    ls.load_program(random_program(FrameEngine<CFG>::kImemWords, rng));
    ls.load_krom(random_words(FrameEngine<CFG>::kKromWords, rng));
    ls.clear_dmem();
    ls.reset();
    ls.run(instructions, by_code);
    if (::testing::Test::HasFailure()) return;
    overflows += ls.model().stack_overflows();
    ls.expect_same_dmem();
  }
  uint64_t least = ~uint64_t(0);
  for (int c = 0; c < 64; ++c) {
    EXPECT_GE(by_code[c], 200u) << "class " << (c >> 4) << " fn " << (c & 15) << " ran too rarely";
    least = std::min(least, by_code[c]);
  }
  // The overflow count was compared at all: the programs did overflow.
  EXPECT_GT(overflows, 0u);
  std::printf("%d programs x %d instructions; every class/function code ran >= %llu times; "
              "%llu return stack overflows\n", programs, instructions,
              static_cast<unsigned long long>(least), static_cast<unsigned long long>(overflows));
}

fa::Program assemble(const std::string& src) {
  fa::Options opt;
  opt.symbols = {{"EV_GO", 1}, {"OUT", 0x100}};
  return fa::assemble(src, "directed.fe", opt);
}

// ---------------------------------------------------------------------------

TEST(FrameEngineRtl, KromInitAndBackDoor) {
  Lockstep<Vframe_engine_tb, SetEbr> ls(1);
  for (uint32_t k = 0; k < 16; ++k) EXPECT_EQ(ls.peek(1, k), kKromInit[k]) << "KROM_INIT word " << k;
  ls.poke(2, 5, 0x12345678u);
  EXPECT_EQ(ls.peek(2, 5), 0x12345678u);
}

// Every field of every KROM_INIT word, through the core's own datapath.
TEST(FrameEngineRtl, DirectedFieldsOfKromInit) {
  std::string src = "        ldx x1, 0\n";
  for (int f = 0; f < 8; ++f) {
    static const char* const names[8] = {"w", "wu", "l", "lu", "h", "l15", "h15", "b"};
    src += std::string("        ld.") + names[f] + " k[x1]\n        out io[OUT + x1]\n";
  }
  src += "        addx x1, 1\n        txa x1\n        sub 16\n        j.lt 1\nhalt:   j halt\n";
  const auto p = assemble(src);
  Lockstep<Vframe_engine_tb, SetEbr> ls(2);
  ls.load_program(p.words);
  ls.model().load_krom(kKromInit, 16);
  ls.clear_dmem();
  ls.reset();
  const uint32_t halt = uint32_t(p.symbols.at("halt"));
  EXPECT_EQ(ls.run_until(halt, 2000), halt);
}

// Shifts and square roots at the edges: counts 0, 1, 15, 47, 48, 63 from
// immediates and from DMEM (and 5), on A = +-2^22 and the 48-bit extremes.
std::string shifts_and_roots_program() {
  std::string src;
  const char* values[] = {"1", "-1", "0x1FFFFFF", "-0x2000000"};
  const int counts[] = {0, 1, 5, 15, 47, 48, 63};
  int slot = 0;
  for (const char* v : values)
    for (int n : counts)
      for (const char* op : {"shl", "shr", "rnd"}) {
        src += std::string("        ld ") + v + "\n        shl 22\n        " + op + " " +
               std::to_string(n) + "\n        st [" + std::to_string(slot % 200) + "]\n";
        src += std::string("        ld ") + std::to_string(n) + "\n        st [250]\n        ld " + v +
               "\n        shl 22\n        " + op + " [250]\n        out io[OUT]\n";
        ++slot;
      }
  for (const char* v : {"0", "1", "2", "3", "-5", "0x1FFFFFF", "33554431"}) {
    src += std::string("        ld ") + v + "\n        sqrt\n        out io[OUT]\n";
    src += std::string("        ld ") + v + "\n        shl 22\n        sqrtr\n        out io[OUT]\n";
    src += std::string("        ld ") + v + "\n        shl 22\n        add 0x3FFFFF\n        sqrt\n";
  }
  src += "        ld -1\n        shr 1\n        sqrt\n        sqrtr\nhalt:   j halt\n";
  return src;
}

template <class V, class CFG>
void shifts_and_roots_at_the_edges() {
  const auto p = assemble(shifts_and_roots_program());
  ASSERT_LE(p.words.size(), 1024u);
  Lockstep<V, CFG> ls(3);
  ls.load_program(p.words);
  ls.clear_dmem();
  ls.reset();
  const uint32_t halt = uint32_t(p.symbols.at("halt"));
  EXPECT_EQ(ls.run_until(halt, 5000), halt);
}

TEST(FrameEngineRtl, DirectedShiftsAndRootsAtTheEdges) {
  shifts_and_roots_at_the_edges<Vframe_engine_tb_dw14, SetSpram>();
}

TEST(FrameEngineRtl, FastShiftDirectedShiftsAndRootsAtTheEdges) {
  shifts_and_roots_at_the_edges<Vframe_engine_tb_fast, SetFast>();
}

// The self-test program, loaded into the RTL by $readmemh (UCODE_HEX) and
// into the model from the same file; it must reach `halt`, not `fail`.
TEST(FrameEngineRtl, SelfTestFromUcodeHex) {
  std::ifstream in(FRAME_ENGINE_SELFTEST_HEX);
  ASSERT_TRUE(in) << FRAME_ENGINE_SELFTEST_HEX;
  std::stringstream ss;
  ss << in.rdbuf();
  const auto words = fa::parse_readmemh(ss.str(), FRAME_ENGINE_SELFTEST_HEX);
  fa::Options opt;
  opt.symbols = {{"EV_GO", 1}, {"OUT", 0x100}};
  opt.imem_words = 1024;
  const auto prog = fa::assemble_file(std::string(ESKIN_SOURCE_DIR) + "/tests/rtl/frame_engine_selftest.fe", opt);
  ASSERT_EQ(words, prog.words);  // the build assembled the same program
  Lockstep<Vframe_engine_tb_dw14, SetSpram> ls(4);
  for (uint32_t i = 0; i < words.size(); ++i) ASSERT_EQ(ls.peek(0, i), words[i]) << "IMEM[" << i << "]";
  ls.model().load_program(words.data(), uint32_t(words.size()));
  ls.clear_dmem();
  ls.reset();
  const uint32_t halt = uint32_t(prog.symbols.at("halt"));
  EXPECT_EQ(ls.run_until(halt, 5000), halt) << "the self-test did not reach halt (fail is at "
                                            << prog.symbols.at("fail") << ")";
  ls.expect_same_dmem();
}

// Return stack overflow: three nested calls. The model counts it (with
// the call's address and clock) and the RTL's count matches; with
// assertions on (as every top is built) the RTL stops at that call with the
// assertion's message. Two nested calls, and calls after returns, trip
// neither.
const char* const kThreeDeep =
    "        call  one\n"
    "halt:   j     halt\n"
    "one:    call  two\n"
    "        ret\n"
    "two:    call  three\n"
    "        ret\n"
    "three:  j     three\n";
const char* const kTwoDeep =
    "        ldx   x1, 20\n"
    "top:    call  one\n"
    "        djnz  x1, top\n"
    "halt:   j     halt\n"
    "one:    call  two\n"
    "        ret\n"
    "two:    ret\n";

TEST(FrameEngineRtl, ThirdNestedCallIsAReturnStackOverflow) {
  const auto p = assemble(kThreeDeep);
  const uint32_t c = uint32_t(p.symbols.at("three")), b = uint32_t(p.symbols.at("two"));
  {
    const AssertionsOff off;
    Lockstep<Vframe_engine_tb, SetEbr> ls(5);
    ls.load_program(p.words);
    ls.clear_dmem();
    ls.reset();
    EXPECT_EQ(ls.run_until(c, 100), c);
    EXPECT_EQ(ls.model().stack_overflows(), 1u);
    EXPECT_EQ(ls.rtl().stk_overflows, 1u);
    EXPECT_EQ(ls.model().stack_overflow_pc(), b);  // `call c`, at b
  }
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  const auto run = [&] {
    dup2(2, 1);  // Verilator prints the assertion on stdout
    Lockstep<Vframe_engine_tb, SetEbr> ls(5);
    ls.load_program(p.words);
    ls.clear_dmem();
    ls.reset();
    ls.run_until(c, 100);
  };
  EXPECT_DEATH(run(),
      "frame_engine: return stack overflow: the call at PC " + std::to_string(b) +
          " is a third nested call");
}

TEST(FrameEngineRtl, TwoNestedCallsAreNoOverflow) {
  const auto p = assemble(kTwoDeep);
  Lockstep<Vframe_engine_tb, SetEbr> ls(6);  // assertions on
  ls.load_program(p.words);
  ls.clear_dmem();
  ls.reset();
  const uint32_t halt = uint32_t(p.symbols.at("halt"));
  EXPECT_EQ(ls.run_until(halt, 500), halt);
  EXPECT_EQ(ls.model().stack_overflows(), 0u);
  EXPECT_EQ(ls.rtl().stk_overflows, 0u);
}

TEST(FrameEngineRtl, RandomProgramsEbrDmem) {
  random_lockstep<Vframe_engine_tb, SetEbr>(100, 20, 50000);
}

TEST(FrameEngineRtl, RandomProgramsSpramDmem) {
  random_lockstep<Vframe_engine_tb_dw14, SetSpram>(200, 12, 50000);
}

// Random programs are about 3/64 shifts of random counts: the barrel
// shifter's every count against the model's result and clocks.
TEST(FrameEngineRtl, FastShiftRandomPrograms) {
  random_lockstep<Vframe_engine_tb_fast, SetFast>(300, 16, 50000);
}

}  // namespace
