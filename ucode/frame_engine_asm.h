// frame_engine_asm: assembler and disassembler for the frame_engine
// microcode (docs/frame_engine.md, "Assembler"). Host-side tool code, like
// the *_config.h builders: it allocates and throws; the kernel it serves is
// ucode/frame_engine.h, whose encoding helpers (eskin::hls::fe) it uses.
//
// Source: one statement per line, `;` starts a comment.
//   label:                     (may precede a statement on the same line)
//   @local:                    (scoped to the last global label, or to one macro expansion)
//   .equ NAME, expr            .org expr (IMEM address)   .word expr[, expr...]
//   .bound expr[, loop]        (for the next instruction: Program::bounds)
//   .if expr / .else / .endif  .include "FILE" (relative to the including file)
//   .macro NAME p1, p2 ... .endm, invoked as `NAME arg1, arg2`; `\p1` in the body
//   ld.h [V + x1]   add k[C]   ld io[PORT]   lt.h15 a   add p   ld 5   shl 12
//   st [V + x2]     out io[PORT]   j.lt label   djnz x2, loop   call f   ret
//   wait 0x1   sqrt   sqrtr   ldx x1, 3   addx x1, -1   tax x3   txa x3   nop
// Aliases of the first ISA draft: ldi/addi (ld/add of an immediate), lpac,
// apac, spac (ld/add/sub p), lta.F (lt.F a), shlm/shrm/rndm (shl/shr/rnd of
// a memory operand).
// Expressions: integers (decimal, 0x hex, 0b binary), symbols, `.` (this
// address), unary - ~, binary * + - << >> & |, parentheses (C precedence).
// Every error names FILE:LINE and what was expected, e.g.
//   "dtmf.fe:42: field: expected one of .w .wu .l .lu .h .l15 .h15 .b, got .x"
// and, in a macro's expansion, the line that expanded it:
//   "m.fe:3: j: target: undefined symbol 'q' (in macro EV expanded at m.fe:9)"
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace eskin::hls::fe_asm {

// Mnemonics by code (the assembler's and the disassembler's one table).
namespace names {
inline constexpr const char* kFieldNames[8] = {"w", "wu", "l", "lu", "h", "l15", "h15", "b"};
inline constexpr const char* kCondNames[8] = {"", "eq", "lt", "le", "nv", "ne", "ge", "gt"};
inline constexpr const char* kDataNames[16] = {"ld", "add", "sub", "min", "max", "and", "or", "xor",
                                    "lt", "mpy", "shl", "shr", "rnd", "st", "out", nullptr};
inline constexpr const char* kCtlNames[11] = {"j",    "djnz", "call", "ret", "wait", "sqrt",
                                   "sqrtr", "ldx", "addx", "tax", "txa"};
inline constexpr const char* kFieldList = "one of .w .wu .l .lu .h .l15 .h15 .b";
}  // namespace names

// An assembly error; what() is "FILE:LINE: message".
class AsmError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Options {
  std::map<std::string, int64_t> symbols;  // predefined, e.g. the top's IO ports
  uint32_t imem_words = 4096;              // 2^IW: addresses and jump targets must fit
  // Reads the file an `.include "NAME"` names: `path` is NAME joined to the
  // including file's directory (lexically normalised). Returns false when
  // there is no such file. Unset: read from the file system. A program built
  // into a binary sets it, so that it assembles without its files on disk.
  std::function<bool(const std::string& path, std::string& text)> read_include;
};

struct ListingLine {
  int line = 0;           // line (1-based) in `file`
  bool has_word = false;  // the line emitted `word` at `addr`
  uint32_t addr = 0;
  uint32_t word = 0;
  std::string text;       // the source line (a macro's: with its arguments in place)
  std::string file;       // the file the line is in (an included file's, a macro's definition's)
  int depth = 0;          // > 0: a line of a macro's expansion, nested this deep
  std::string expanded_at;  // depth > 0: "FILE:LINE" of the invocation it came from
};

struct Program {
  std::string file;             // the top source's name, as assemble() was given it
  std::vector<uint32_t> words;  // IMEM image, address 0 .. highest address written
  std::map<std::string, int64_t> symbols;  // labels, .equ and predefined symbols
  // One entry per source line (and per extra .word), in assembly order: a
  // macro's invocation, then its expansion's lines; an .include, then the
  // included file's lines.
  std::vector<ListingLine> listing;
  // `.bound COUNT[, LOOP]` before an instruction (ucode/frame_bound.h), by
  // its address: a branch that closes a loop is taken at most COUNT times
  // per entry of its loop (with LOOP, in all per entry of the loop around
  // it that jumps back to address LOOP); a shift by a memory / P count
  // shifts by at most COUNT.
  struct Bound {
    int64_t count = 0;
    int64_t per = -1;  // LOOP, -1 without
  };
  std::map<uint32_t, Bound> bounds;
};

// `file` names the source in errors and is where its .include names are
// resolved from.
Program assemble(const std::string& source, const std::string& file, const Options& opt = {});
// Reads `path` and assembles it (AsmError if it cannot be read).
Program assemble_file(const std::string& path, const Options& opt = {});

// Listing: address, word, line number and source per line, then the symbols.
// A line of a macro's expansion shows its line in the macro with a `+` per
// level of expansion; a line of an included file shows FILE:LINE.
std::string listing_text(const Program& prog);
// $readmemh image: one 8-digit hex word per line from address 0.
std::string readmemh_text(const std::vector<uint32_t>& words);
// Parses a $readmemh image (hex words separated by white space, `//`
// comments; no @address); errors name FILE:LINE.
std::vector<uint32_t> parse_readmemh(const std::string& text, const std::string& file);

// One instruction word as assembler text that assembles back to the same
// word; a word the assembler cannot produce (bits the hardware ignores set,
// out-of-range operands) prints as `.word 0x...` with its meaning after `;`.
std::string disassemble(uint32_t word);

}  // namespace eskin::hls::fe_asm
