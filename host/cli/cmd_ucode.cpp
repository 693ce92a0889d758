// `eskin ucode`: the frame_engine microcode tools (docs/frame_engine.md).
//   eskin ucode asm FILE.fe [-o FILE.hex] [--list FILE.lst] [-D NAME=VALUE]... [--iw N]
//     assembles FILE.fe into a $readmemh image (default: FILE's name with
//     .hex in the current directory, never beside the source),
//     optionally with a listing; -D predefines symbols (e.g. IO ports).
//   eskin ucode run FILE.fe [--trace] [--max-clocks N] [--krom FILE.hex]
//                           [--events MASK] [-D ...]
//     runs it on the instruction-set model (ucode/frame_engine.h; IMEM 4096,
//     DMEM 32768 and KROM 4096 words, the largest configuration) with nothing
//     on the IO bus: reads give 0, writes are printed, the events are MASK in
//     every clock (default 0). It stops at a jump to itself (the halt idiom),
//     at a wait no event can end, or after N clocks; --trace prints every
//     instruction.
//   eskin ucode build SCENE.yaml [--out DIR] [--clk-mhz F]
//     the DTMF top's build for a scene (common/eskin/dtmf_top_plan.h's plan at
//     the given clock, default the UP5K's): writes DIR/NAME.ucode.hex and
//     DIR/NAME.krom.hex (NAME = the scene's file stem; rtl/ucode/dtmf_chain.fe
//     assembled with the scene's constants) and prints every Verilog
//     parameter of rtl/dtmf_top.v as NAME=VALUE, one per line, for a
//     synthesis script (scripts/fit_check.sh).
//   eskin ucode io-map [--out FILE]
//     writes rtl/dtmf_io_map.vh (or FILE), the frame engine's IO map as the
//     top's Verilog includes it, from its one definition (ucode/dtmf_io_map.h).
#include <fmt/core.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.h"
#include "eskin/skin_config.h"
#include "eskin/source_tree.h"
#include "ucode/frame_engine.h"
#include "ucode/frame_engine_asm.h"
#include "ucode/dtmf_io_map.h"
#include "ucode/dtmf_ucode.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"

#include <filesystem>

namespace {

namespace fe = eskin::hls::fe;
namespace fa = eskin::hls::fe_asm;

struct RunConfig {  // the largest legal configuration
  static constexpr int IW = 12;
  static constexpr int DW = 15;
  static constexpr int KW = 12;
  static constexpr bool FAST_SHIFT = false;  // `run` counts the UP5K build's clocks
};
using Engine = eskin::hls::FrameEngine<RunConfig>;

struct UcodeArgs {
  std::string file, out, list, krom;
  double clk_mhz = eskin::hls::kDtmfTopClkHz / 1e6;
  std::vector<std::string> defines;
  int iw = 12;
  bool trace = false;
  uint64_t max_clocks = 10'000'000;
  uint16_t events = 0;
};

fa::Options options(const UcodeArgs& a) {
  fa::Options opt;
  if (a.iw < 4 || a.iw > 12) throw eskin::ConfigError("--iw", fmt::format("expected 4..12, got {}", a.iw));
  opt.imem_words = 1u << a.iw;
  for (const auto& d : a.defines) {
    const size_t eq = d.find('=');
    const std::string name = d.substr(0, eq);
    // The value is an assembler expression of numbers (0x.., 0b.., -..).
    int64_t value = 0;
    if (eq == std::string::npos || name.empty()) {
      throw eskin::ConfigError("-D", "expected NAME=VALUE, got '" + d + "'");
    }
    try {
      const auto p = fa::assemble(".equ V, " + d.substr(eq + 1) + "\n", "-D " + name);
      value = p.symbols.at("V");
    } catch (const fa::AsmError& e) {
      throw eskin::ConfigError("-D", std::string(e.what()));
    }
    opt.symbols[name] = value;
  }
  return opt;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  if (!f || !(f << text)) throw std::runtime_error(path + ": cannot write");
}

int run_asm(const UcodeArgs& a) {
  const auto prog = fa::assemble_file(a.file, options(a));
  std::string out = a.out;
  // The source may be in a tree the user does not mean to write (rtl/,
  // the repository): the default image goes where the user is.
  if (out.empty()) out = std::filesystem::path(a.file).stem().string() + ".hex";
  write_file(out, fa::readmemh_text(prog.words));
  if (!a.list.empty()) write_file(a.list, fa::listing_text(prog));
  fmt::print("{}: {} words, {} symbols -> {}\n", a.file, prog.words.size(), prog.symbols.size(), out);
  return 0;
}

// Nothing on the bus but constant events; writes are printed as they happen.
struct PrintingNullIo {
  uint16_t ev = 0;
  uint32_t io_read(uint16_t, uint64_t) { return 0; }
  void io_write(uint16_t addr, uint32_t data, uint64_t clock) {
    fmt::print("io[0x{:04x}] <= 0x{:08x} ({}) at clock {}\n", addr, data, int32_t(data), clock);
  }
  uint16_t events(uint64_t) { return ev; }
};

std::string registers(const Engine& e) {
  return fmt::format("A={} P={} T={} X1={} X2={} X3={}", e.a(), e.p(), e.t(), e.x(1), e.x(2), e.x(3));
}

int run_run(const UcodeArgs& a) {
  const auto prog = fa::assemble_file(a.file, options(a));
  auto e = std::make_unique<Engine>();
  e->load_program(prog.words.data(), uint32_t(prog.words.size()));
  if (!a.krom.empty()) {
    std::ifstream in(a.krom);
    if (!in) throw eskin::ConfigError("--krom", a.krom + ": cannot read the file");
    std::stringstream ss;
    ss << in.rdbuf();
    const auto words = fa::parse_readmemh(ss.str(), a.krom);
    if (words.size() > Engine::kKromWords)
      throw eskin::ConfigError("--krom", fmt::format("{}: expected at most {} words, got {}", a.krom,
                                                     Engine::kKromWords, words.size()));
    e->load_krom(words.data(), uint32_t(words.size()));
  }
  e->reset();
  PrintingNullIo io;
  io.ev = a.events;
  uint64_t instructions = 0;
  std::string why = fmt::format("stopped after {} clocks (--max-clocks)", a.max_clocks);
  if (a.trace) fmt::print("{:>8} {:>4} {:>8}  {:<28} {}\n", "clock", "pc", "word", "instruction", "after");
  while (e->clocks() < a.max_clocks) {
    const uint32_t pc = e->pc(), w = e->imem(pc);
    if (fe::cls_of(w) == fe::kCtl && fe::fn_of(w) == fe::kWait && (fe::addr_of(w) & a.events) == 0) {
      why = fmt::format("stopped at {}: wait 0x{:x}, and --events is 0x{:x}", pc, fe::addr_of(w), a.events);
      break;
    }
    const uint64_t clock = e->clocks();
    e->step(io);
    ++instructions;
    if (a.trace) {
      std::string after = registers(*e);
      if (e->last().stored) after += fmt::format(" [{}]<=0x{:08x}", e->last().st_addr, e->last().st_data);
      fmt::print("{:>8} {:>4} {:08x}  {:<28} {}\n", clock, pc, w, fa::disassemble(w), after);
    }
    if (fe::cls_of(w) == fe::kCtl && fe::fn_of(w) == fe::kJ && fe::field_of(w) == fe::kAlways &&
        e->pc() == pc) {
      why = fmt::format("halted at {}: jump to itself", pc);
      break;
    }
  }
  fmt::print("{}; {} instructions, {} clocks; {}\n", why, instructions, e->clocks(), registers(*e));
  return 0;
}

int run_build(const UcodeArgs& a) {
  const eskin::sim::Scene scene = eskin::sim::load_scene(a.file);  // names the bad field
  const long clk = std::lround(a.clk_mhz * 1e6);
  eskin::hls::DtmfTopPlan plan;
  try {
    plan = eskin::hls::make_dtmf_top_plan(eskin::sim::dtmf_top_spec(scene, clk));
  } catch (const std::invalid_argument& e) {
    throw eskin::ConfigError(a.file, e.what());
  }
  const std::string dir = std::filesystem::absolute(a.out.empty() ? "." : a.out).string();
  std::filesystem::create_directories(dir);
  const std::string name = std::filesystem::path(a.file).stem().string();
  for (const auto& p : eskin::hls::write_dtmf_top_build(plan, dir, name))
    fmt::print("{}={}\n", p.name, p.value);
  return 0;
}

int run_io_map(const UcodeArgs& a) {
  const std::string out = a.out.empty() ? eskin::source_dir() + "/rtl/dtmf_io_map.vh" : a.out;
  std::ofstream f(out, std::ios::binary);
  f << eskin::hls::dtmf_io_map_verilog();
  f.close();
  if (!f) throw eskin::ConfigError(out, "cannot write the IO map include");
  fmt::print("{}\n", out);
  return 0;
}

std::function<int()> setup_ucode(CLI::App& app) {
  auto args = std::make_shared<UcodeArgs>();
  CLI::App* sub = app.add_subcommand("ucode", "frame_engine microcode: assemble, run on the model");
  sub->require_subcommand(1);
  auto add_common = [&](CLI::App* c) {
    c->add_option("file", args->file, "Microcode source (.fe)")->required();
    c->add_option("-D", args->defines, "Predefine a symbol: NAME=VALUE (repeatable)");
  };
  CLI::App* as = sub->add_subcommand("asm", "Assemble FILE.fe into a $readmemh image");
  add_common(as);
  as->add_option("-o", args->out, "Output image (default: FILE's name with .hex, in the current directory)");
  as->add_option("--list", args->list, "Also write a listing (addresses, words, symbols)");
  as->add_option("--iw", args->iw, "IMEM address bits of the target (4..12)")->capture_default_str();
  CLI::App* rn = sub->add_subcommand("run", "Run FILE.fe on the instruction-set model, null IO");
  add_common(rn);
  rn->add_flag("--trace", args->trace, "Print every instruction with the registers after it");
  rn->add_option("--max-clocks", args->max_clocks, "Stop after this many clocks")->capture_default_str();
  rn->add_option("--krom", args->krom, "KROM contents ($readmemh image)");
  rn->add_option("--events", args->events, "Events raised in every clock (a 16-bit mask)")
      ->capture_default_str();
  CLI::App* bd = sub->add_subcommand("build", "Write the DTMF top's microcode and constants for a scene");
  bd->add_option("scene", args->file, "Scene (.yaml)")->required();
  bd->add_option("--out", args->out, "Directory for NAME.ucode.hex and NAME.krom.hex (default .)");
  bd->add_option("--clk-mhz", args->clk_mhz, "FPGA clock the plan is made for")->capture_default_str();
  CLI::App* io = sub->add_subcommand("io-map", "Write the IO map's Verilog include (rtl/dtmf_io_map.vh)");
  io->add_option("--out", args->out, "Output file (default: rtl/dtmf_io_map.vh of the source tree)");
  return [args, as, bd, io] {
    try {
      if (io->parsed()) return run_io_map(*args);
      if (bd->parsed()) return run_build(*args);
      return as->parsed() ? run_asm(*args) : run_run(*args);
    } catch (const fa::AsmError& e) {
      throw eskin::ConfigError("microcode", e.what());
    }
  };
}

}  // namespace

ESKIN_COMMAND("ucode", setup_ucode);
