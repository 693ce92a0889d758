// frame_engine_asm: disassembler, listing and $readmemh images (see the header).
#include <cctype>
#include <cstdio>
#include <sstream>

#include "ucode/frame_engine.h"
#include "ucode/frame_engine_asm.h"

namespace eskin::hls::fe_asm {
namespace {

using namespace eskin::hls::fe;
using namespace eskin::hls::fe_asm::names;

std::string hex32(uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "%08x", v);
  return b;
}

}  // namespace

std::string listing_text(const Program& prog) {
  std::string out;
  char b[64];
  for (const auto& l : prog.listing) {
    // The line column: N, FILE:N for an included file's line, N+ (a `+` a
    // level) for a line of a macro's expansion.
    std::string at = std::to_string(l.line);
    if (!l.file.empty() && l.file != prog.file) at = l.file + ":" + at;
    at += std::string(size_t(l.depth), '+');
    if (l.has_word) std::snprintf(b, sizeof b, "%04x  %08x  ", l.addr, l.word);
    else std::snprintf(b, sizeof b, "%4s  %8s  ", "", "");
    out += b + (at.size() < 5 ? std::string(5 - at.size(), ' ') : std::string()) + at + "  " +
           l.text + "\n";
  }
  out += "\nsymbols:\n";
  for (const auto& [name, value] : prog.symbols) {
    std::snprintf(b, sizeof b, "  %-24s %lld (0x%llx)\n", name.c_str(), static_cast<long long>(value),
                  static_cast<unsigned long long>(value));
    out += b;
  }
  return out;
}

std::string readmemh_text(const std::vector<uint32_t>& words) {
  std::string out;
  for (uint32_t w : words) out += hex32(w) + "\n";
  return out;
}

std::vector<uint32_t> parse_readmemh(const std::string& text, const std::string& file) {
  std::vector<uint32_t> words;
  std::istringstream in(text);
  std::string line;
  for (int ln = 1; std::getline(in, line); ++ln) {
    line = line.substr(0, line.find("//"));
    std::istringstream ls(line);
    std::string tok;
    while (ls >> tok) {
      uint64_t v = 0;
      for (char c : tok) {
        const char l = char(std::tolower(static_cast<unsigned char>(c)));
        int d = (l >= '0' && l <= '9') ? l - '0' : (l >= 'a' && l <= 'f') ? 10 + l - 'a' : -1;
        if (c == '_') continue;
        if (d < 0 || v > 0xFFFFFFFull)
          throw AsmError(file + ":" + std::to_string(ln) +
                         ": expected a hex word of at most 8 digits, got '" + tok + "'");
        v = v * 16 + uint64_t(d);
      }
      words.push_back(uint32_t(v));
    }
  }
  return words;
}

std::string disassemble(uint32_t w) {
  const uint32_t cls = cls_of(w), fn = fn_of(w), x = x_of(w), f = field_of(w), addr = addr_of(w);
  std::string text;
  uint32_t canonical = ~w;  // the word the assembler makes of `text`
  auto suffix = [&](uint32_t field) { return field == kW ? std::string() : std::string(".") + kFieldNames[field]; };
  auto xname = [](uint32_t i) { return "x" + std::to_string(i); };
  auto memop = [&](uint32_t space) {
    const char* prefix = space == kKrom ? "k[" : space == kIo ? "io[" : "[";
    // With an index, a high address reads better as a negative offset.
    if (x != 0 && addr >= 0x8000) return prefix + xname(x) + " - " + std::to_string(0x10000 - addr) + "]";
    std::string t = prefix + std::to_string(addr);
    if (x != 0) t += " + " + xname(x);
    return t + "]";
  };
  if (cls == kMem && fn <= kOut) {
    const uint32_t space = space_of(w);
    if (fn == kSt || fn == kOut) {
      text = std::string(kDataNames[fn]) + " " + memop(space);
      const bool right_space = space == (fn == kSt ? kDmem : kIo);
      canonical = right_space ? mem(fn, space, x, 0, addr) : ~w;
    } else if (space == kAcc) {
      text = std::string(kDataNames[fn]) + suffix(f) + " a";
      canonical = mem(fn, kAcc, 0, f, 0);
    } else {
      text = std::string(kDataNames[fn]) + suffix(f) + " " + memop(space);
      canonical = mem(fn, space, x, f, addr);
    }
  } else if (cls == kImm && fn <= kRnd) {
    const int32_t v = imm_of(w);
    text = std::string(kDataNames[fn]) + " " + std::to_string(v);
    const bool shift = fn == kShl || fn == kShr || fn == kRnd;
    const bool in_range = shift ? (v >= 0 && v <= 63) : (fn == kLt || fn == kMpy) ? (v >= -32768 && v <= 65535) : true;
    canonical = in_range ? imm(fn, v) : ~w;
  } else if (cls == kP && fn <= kRnd) {
    text = std::string(kDataNames[fn]) + suffix(f) + " p";
    canonical = preg(fn, f);
  } else if (cls == kCtl && fn <= kTxa) {
    // Targets beyond the largest IMEM (IW <= 12) are no assembler output.
    const bool target_ok = addr < 4096;
    switch (fn) {
      case kJ:
        text = std::string("j") + (f ? std::string(".") + kCondNames[f] : "") + " " + std::to_string(addr);
        canonical = target_ok ? ctl(kJ, 0, f, addr) : ~w;
        break;
      case kDjnz:
        text = "djnz " + xname(x) + ", " + std::to_string(addr);
        canonical = target_ok ? ctl(kDjnz, x, 0, addr) : ~w;
        break;
      case kCall:
        text = "call " + std::to_string(addr);
        canonical = target_ok ? ctl(kCall, 0, 0, addr) : ~w;
        break;
      case kWait: {
        char b[16];
        std::snprintf(b, sizeof b, "0x%x", addr);
        text = std::string("wait ") + b;
        canonical = addr != 0 ? ctl(kWait, 0, 0, addr) : ~w;
        break;
      }
      case kLdx: case kAddx:
        text = std::string(kCtlNames[fn]) + " " + xname(x) + ", " + std::to_string(addr);
        canonical = ctl(fn, x, 0, addr);
        break;
      case kTax: case kTxa:
        text = std::string(kCtlNames[fn]) + " " + xname(x);
        canonical = ctl(fn, x, 0, 0);
        break;
      default:  // ret, sqrt, sqrtr
        text = kCtlNames[fn];
        canonical = ctl(fn, 0, 0, 0);
        break;
    }
  } else if (cls == kCtl && fn == kNopCtl) {
    text = "nop";
    canonical = ctl(kNopCtl, 0, 0, 0);
  } else {
    text = "nop";  // the remaining function codes do nothing
  }
  if (canonical == w) return text;
  return ".word 0x" + hex32(w) + " ; " + text;
}

}  // namespace eskin::hls::fe_asm
