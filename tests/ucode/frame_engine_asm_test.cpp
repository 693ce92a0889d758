// The assembler's macros, local labels and .include (ucode/frame_engine_asm.h,
// docs/frame_engine.md "Assembler"): the words each program assembles to,
// against words packed by hand from the manual's encoding table ([31:30]
// class, [29:26] fn, [25:24] space, [23:22] x, [21:19] field/cond, [15:0]
// addr; imm26 at [25:0]), the listing of an expansion, and every error
// message with the file and line it names.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

#include "ucode/frame_engine_asm.h"

namespace {

namespace fa = eskin::hls::fe_asm;
namespace fs = std::filesystem;

// Hand-packed words.
constexpr uint32_t imm(uint32_t fn, int32_t v) { return 0x40000000u | fn << 26 | (uint32_t(v) & 0x3FFFFFFu); }
constexpr uint32_t kLd = 0, kAdd = 1;
constexpr uint32_t kNop = 0xEC000000u, kRet = 0xCC000000u;
constexpr uint32_t j(uint32_t t, uint32_t cond = 0) { return 0xC0000000u | cond << 19 | t; }
constexpr uint32_t djnz(uint32_t x, uint32_t t) { return 0xC4000000u | x << 22 | t; }
constexpr uint32_t ldx(uint32_t x, uint32_t v) { return 0xDC000000u | x << 22 | v; }
constexpr uint32_t kGe = 6;

std::string error_of(const std::string& src, const fa::Options& opt = {}) {
  try {
    fa::assemble(src, "t.fe", opt);
  } catch (const fa::AsmError& e) {
    return e.what();
  }
  return "no error";
}

// A directory of real files for .include, removed afterwards.
struct TempDir {
  fs::path dir = fs::temp_directory_path() / ("fe_asm_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(dir); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.generic_string();
  }
};

TEST(FrameEngineAsmMacro, ExpandsItsBodyWithTheArgumentsInPlace) {
  const std::string src =
      "        .macro ADD2 v, w          ; two adds\n"
      "        add   \\v\n"
      "        add   \\w\n"
      "        .endm\n"
      "start:  ld    1\n"
      "        ADD2  2, 3 + 1\n"
      "twice:  ADD2  k[5], -1            ; a label before an invocation\n"
      "        .macro NONE\n"
      "        nop\n"
      "        .endm\n"
      "        NONE\n"
      "end:    j     end\n";
  const auto p = fa::assemble(src, "t.fe");
  EXPECT_EQ(p.words, (std::vector<uint32_t>{imm(kLd, 1), imm(kAdd, 2), imm(kAdd, 4), 0x05000005u,
                                            imm(kAdd, -1), kNop, j(6)}));
  EXPECT_EQ(p.symbols.at("twice"), 3);
  EXPECT_EQ(p.symbols.at("end"), 6);
}

// A macro with a loop expanded three times, twice through another macro:
// each expansion's @lp is its own.
TEST(FrameEngineAsmMacro, NestedExpansionsEachHaveTheirOwnLocalLabels) {
  const std::string src =
      "        .macro DELAY n\n"
      "        ldx   x2, \\n\n"
      "@lp:    nop\n"
      "        djnz  x2, @lp\n"
      "        .endm\n"
      "        .macro TWICE n\n"
      "        DELAY \\n\n"
      "        DELAY \\n + 1\n"
      "        .endm\n"
      "        DELAY 3\n"
      "        TWICE 5\n";
  const auto p = fa::assemble(src, "t.fe");
  EXPECT_EQ(p.words, (std::vector<uint32_t>{ldx(2, 3), kNop, djnz(2, 1), ldx(2, 5), kNop, djnz(2, 4),
                                            ldx(2, 6), kNop, djnz(2, 7)}));
}

// @labels outside macros belong to the last global label; a macro's
// argument is scoped where the macro is invoked; another scope's local
// label is reachable by its full name.
TEST(FrameEngineAsmMacro, LocalLabelsAreScopedToTheLastGlobalLabel) {
  const std::string src =
      "        .macro JGE t\n"
      "        j.ge  \\t\n"
      "        .endm\n"
      "f:      ldx   x1, 2\n"
      "@lp:    djnz  x1, @lp\n"
      "        ret\n"
      "g:      ldx   x1, 3\n"
      "@lp:    djnz  x1, @lp\n"
      "        j     @lp\n"
      "        j     f@lp\n"
      "        JGE   @out\n"
      "        nop\n"
      "@out:   ret\n";
  const auto p = fa::assemble(src, "t.fe");
  EXPECT_EQ(p.words, (std::vector<uint32_t>{ldx(1, 2), djnz(1, 1), kRet, ldx(1, 3), djnz(1, 4), j(4),
                                            j(1), j(9, kGe), kNop, kRet}));
  EXPECT_EQ(p.symbols.at("f@lp"), 1);
  EXPECT_EQ(p.symbols.at("g@lp"), 4);
  EXPECT_EQ(p.symbols.at("g@out"), 9);
  // .if and .equ see them too.
  EXPECT_EQ(fa::assemble("g:  nop\n@x: nop\n    .equ @y, @x + 1\n    .if @y - 2\n    ld 9\n"
                         "    .else\n    ld 7\n    .endif\n",
                         "t.fe")
                .words,
            (std::vector<uint32_t>{kNop, kNop, imm(kLd, 7)}));
}

TEST(FrameEngineAsmMacro, ConditionalsInsideAMacroSeeItsArguments) {
  const std::string src =
      "        .macro MAYBE n\n"
      "        .if   \\n\n"
      "        add   \\n\n"
      "        .else\n"
      "        nop\n"
      "        .endif\n"
      "        .endm\n"
      "        MAYBE 0\n"
      "        MAYBE 7\n"
      "        .if   0\n"
      "        MAYBE 1, 2                ; not taken: not even checked\n"
      "        .endif\n";
  EXPECT_EQ(fa::assemble(src, "t.fe").words, (std::vector<uint32_t>{kNop, imm(kAdd, 7)}));
}

// The listing shows the invocation, then each line of the expansion with its
// line in the macro (a `+` a level) and its arguments in place.
TEST(FrameEngineAsmMacro, ListingShowsTheExpandedLinesWithTheirSourceLines) {
  const std::string src =
      "        .macro INC r\n"
      "        add   \\r                 ; one more\n"
      "        .endm\n"
      "        .macro INC2 r\n"
      "        INC   \\r\n"
      "        INC   \\r\n"
      "        .endm\n"
      "go:     INC2  3\n";
  const auto p = fa::assemble(src, "t.fe");
  const std::string lst = fa::listing_text(p);
  const std::string none(16, ' ');  // no address, no word
  EXPECT_NE(lst.find(none + "    8  go:     INC2  3\n" +
                     none + "   5+          INC   3\n" +
                     "0000  44000003    2++          add   3                 ; one more\n" +
                     none + "   6+          INC   3\n" +
                     "0001  44000003    2++          add   3                 ; one more\n"),
            std::string::npos)
      << lst;
  ASSERT_EQ(p.listing.size(), 12u);  // 7 definition lines, the invocation, 2 + 2 expanded
  const fa::ListingLine& l = p.listing[9];
  EXPECT_TRUE(l.has_word);
  EXPECT_EQ(l.line, 2);
  EXPECT_EQ(l.depth, 2);
  EXPECT_EQ(l.expanded_at, "t.fe:5");
  EXPECT_EQ(p.listing[8].expanded_at, "t.fe:8");
}

TEST(FrameEngineAsmInclude, FilesResolveFromTheIncludingFile) {
  TempDir t;
  t.write("lib/macros.fe",
          "        .macro TWO\n"
          "        ld    2\n"
          "        .endm\n"
          "        .include \"consts.fe\"        ; beside macros.fe\n");
  t.write("lib/consts.fe", "        .equ  K, 5\n");
  const std::string main = t.write("src/main.fe",
                                   "        .include \"../lib/macros.fe\"\n"
                                   "        TWO\n"
                                   "        add   K\n"
                                   "        .include \"../lib/macros2.fe\"\n");
  t.write("lib/macros2.fe", "        ld    K + 1\n");
  const auto p = fa::assemble_file(main);
  EXPECT_EQ(p.words, (std::vector<uint32_t>{imm(kLd, 2), imm(kAdd, 5), imm(kLd, 6)}));
  const std::string lst = fa::listing_text(p);
  const std::string consts = (t.dir / "lib/consts.fe").generic_string();
  EXPECT_NE(lst.find(consts + ":1          .equ  K, 5\n"), std::string::npos) << lst;
}

// A program built into a binary reads its .include files from the
// callback, which gets the name joined to the including file's directory.
TEST(FrameEngineAsmInclude, TheCallbackReadsWhatTheProgramIncludes) {
  const std::map<std::string, std::string> files = {
      {"rtl/ucode/m.fe", ".macro ONE\nld 1\n.endm\n"},
      {"rtl/x.fe", "ONE\n"},
  };
  std::vector<std::string> asked;
  fa::Options opt;
  opt.read_include = [&](const std::string& path, std::string& text) {
    asked.push_back(path);
    const auto it = files.find(path);
    if (it == files.end()) return false;
    text = it->second;
    return true;
  };
  const auto p = fa::assemble(".include \"m.fe\"\n.include \"../x.fe\"\n", "rtl/ucode/top.fe", opt);
  EXPECT_EQ(p.words, (std::vector<uint32_t>{imm(kLd, 1)}));
  EXPECT_EQ(asked, (std::vector<std::string>{"rtl/ucode/m.fe", "rtl/x.fe"}));  // each read once
}

TEST(FrameEngineAsmMacro, ErrorsNameTheLineAndTheExpansion) {
  EXPECT_EQ(error_of(".macro M u, w\nadd \\u\n.endm\nM 1\n"),
            "t.fe:4: M: expected 2 arguments (u, w), got 1");
  EXPECT_EQ(error_of(".macro M\nnop\n.endm\nM 1\n"), "t.fe:4: M: expected 0 arguments, got 1");
  EXPECT_EQ(error_of(".macro M u\n.endm\nM 1,\n"), "t.fe:3: M: expected 1 argument (u), got 2");
  EXPECT_EQ(error_of(".macro M u, w\n.endm\nM 1,,2\n"), "t.fe:3: M: expected 2 arguments (u, w), got 3");
  EXPECT_EQ(error_of(".macro M u, w\n.endm\nM 1,\n"), "t.fe:3: M: argument 2 is empty");
  EXPECT_EQ(error_of("nop\n.macro M\nnop\n"), "t.fe:2: .macro M: no .endm before the end of the file");
  EXPECT_EQ(error_of("nop\n.endm\n"), "t.fe:2: .endm: no .macro before it");
  EXPECT_EQ(error_of(".macro M\n.endm 3\n"), "t.fe:2: .endm: expected nothing after it, got '3'");
  EXPECT_EQ(error_of(".macro\n"), "t.fe:1: .macro: expected a name");
  EXPECT_EQ(error_of(".macro 9x\n"),
            "t.fe:1: .macro: expected a name (a letter or '_', then letters, digits, '_'), got '9x'");
  EXPECT_EQ(error_of(".macro ld\n.endm\n"), "t.fe:1: .macro ld: the name of an instruction");
  EXPECT_EQ(error_of(".macro M u, u\n.endm\n"), "t.fe:1: .macro M: parameter 'u' twice");
  EXPECT_EQ(error_of(".macro M a\n.endm\n"), "t.fe:1: .macro M: expected a parameter name, got 'a'");
  EXPECT_EQ(error_of(".macro M u, x1\n.endm\n"), "t.fe:1: .macro M: expected a parameter name, got 'x1'");
  EXPECT_EQ(error_of(".macro M\n.endm\n.macro M\n.endm\n"), "t.fe:3: .macro M: already defined at t.fe:1");
  EXPECT_EQ(error_of(".macro M\n.macro N\n.endm\n.endm\n"),
            "t.fe:2: .macro: inside the definition of M (line 1); expected its .endm first");
  EXPECT_EQ(error_of("M 1\n.macro M a\n.endm\n"), "t.fe:1: unknown instruction 'M'");  // define, then use
  // An error in an expansion: the line in the macro, then each line that expanded it.
  EXPECT_EQ(error_of(".macro M\nnop\nj nowhere\n.endm\nnop\nM\n"),
            "t.fe:3: j: target: undefined symbol 'nowhere' (in macro M expanded at t.fe:6)");
  EXPECT_EQ(error_of(".macro IN u\nld.x [\\u]\n.endm\n.macro OUT\nIN 4\n.endm\nOUT\n"),
            "t.fe:2: ld: field: expected one of .w .wu .l .lu .h .l15 .h15 .b, got .x "
            "(in macro IN expanded at t.fe:5, in macro OUT expanded at t.fe:7)");
  EXPECT_EQ(error_of(".macro M u\nadd \\b\n.endm\nM 1\n"),
            "t.fe:2: M: '\\b' is not a parameter (expected one of \\u) (in macro M expanded at t.fe:4)");
  EXPECT_EQ(error_of(".macro M\nadd \\b\n.endm\nM\n"),
            "t.fe:2: M: '\\b' is not a parameter (it has none) (in macro M expanded at t.fe:4)");
  // Recursion, direct or through another macro, stops at once.
  EXPECT_EQ(error_of(".macro MA\nMA\n.endm\nMA\n"),
            "t.fe:2: MA: a macro cannot expand itself (MA -> MA) (in macro MA expanded at t.fe:4)");
  EXPECT_EQ(error_of(".macro MA\nMB\n.endm\n.macro MB\nMA\n.endm\nnop\nMA\n"),
            "t.fe:5: MA: a macro cannot expand itself (MA -> MB -> MA) "
            "(in macro MB expanded at t.fe:2, in macro MA expanded at t.fe:8)");
  // Nesting is bounded (a cycle the name checks cannot see: one file under two names).
  std::string deep;
  for (int i = 0; i < 70; ++i)  // M_i's .macro at line 3 i + 1, its body (M_i+1) at 3 i + 2
    deep += ".macro M" + std::to_string(i) + "\nM" + std::to_string(i + 1) + "\n.endm\n";
  deep += ".macro M70\nnop\n.endm\nM0\n";
  const std::string too_deep = error_of(deep);  // M63's line invoking M64, 64 macros open
  EXPECT_EQ(too_deep.rfind("t.fe:191: macros and .include nested more than 64 deep (in macro M63 expanded at "
                           "t.fe:188, in macro M62 ", 0), 0u) << too_deep;
  deep.resize(deep.find(".macro M63\n"));
  deep += ".macro M63\nnop\n.endm\nM0\n";
  EXPECT_EQ(fa::assemble(deep, "t.fe").words, (std::vector<uint32_t>{kNop}));  // 64 macros open: not too deep
  // A .if block closes where it opened.
  EXPECT_EQ(error_of(".macro M\n.if 1\n.endm\nM\n"),
            "t.fe:2: .if: no .endif before the end of macro M (in macro M expanded at t.fe:4)");
  EXPECT_EQ(error_of(".macro M\n.endif\n.endm\n.if 1\nM\n.endif\n"),
            "t.fe:2: .endif: no .if before it (in macro M expanded at t.fe:5)");
  // Local labels.
  EXPECT_EQ(error_of("@x: nop\n"), "t.fe:1: local label '@x': no global label above it to scope it");
  EXPECT_EQ(error_of("f: nop\nj @\n"),
            "t.fe:2: local label: expected a name after '@' (a letter or '_' first), got '@'");
  EXPECT_EQ(error_of("f: nop\n@1: nop\n"),
            "t.fe:2: local label: expected a name after '@' (a letter or '_' first), got '@1'");
  EXPECT_EQ(error_of("f:\n@x: nop\n@x: nop\n"), "t.fe:3: label 'f@x': already defined");
  EXPECT_EQ(error_of("f:\n@x: nop\ng: j @x\n"), "t.fe:3: j: target: undefined symbol 'g@x'");
}

TEST(FrameEngineAsmInclude, ErrorsNameTheFileAndTheLine) {
  TempDir t;
  const std::string d = t.dir.generic_string();
  const std::string top = t.write("top.fe", "nop\n.include \"missing.fe\"\n");
  try {
    fa::assemble_file(top);
    ADD_FAILURE() << "no error";
  } catch (const fa::AsmError& e) {
    EXPECT_EQ(std::string(e.what()), top + ":2: .include: cannot read \"" + d + "/missing.fe\"");
  }
  const std::string a = t.write("a.fe", "nop\n.include \"sub/b.fe\"\n");
  t.write("sub/b.fe", ".include \"../a.fe\"\n");
  try {
    fa::assemble_file(a);
    ADD_FAILURE() << "no error";
  } catch (const fa::AsmError& e) {
    EXPECT_EQ(std::string(e.what()), d + "/sub/b.fe:1: .include: an include cycle (" + d + "/a.fe -> " + d +
                                         "/sub/b.fe -> " + d + "/a.fe) (included from " + d + "/a.fe:2)");
  }
  const std::string self = t.write("self.fe", ".include \"self.fe\"\n");
  try {
    fa::assemble_file(self);
    ADD_FAILURE() << "no error";
  } catch (const fa::AsmError& e) {
    EXPECT_EQ(std::string(e.what()), self + ":1: .include: an include cycle (" + self + " -> " + self + ")");
  }
  // An error in an included file: its line, then the .include's.
  const std::string outer = t.write("outer.fe", "nop\n.include \"bad.fe\"\n");
  t.write("bad.fe", "nop\nnop\nfrob\n");
  try {
    fa::assemble_file(outer);
    ADD_FAILURE() << "no error";
  } catch (const fa::AsmError& e) {
    EXPECT_EQ(std::string(e.what()),
              d + "/bad.fe:3: unknown instruction 'frob' (included from " + outer + ":2)");
  }
  const std::string open_if = t.write("open_if.fe", ".if 1\n");
  const std::string inc_if = t.write("inc_if.fe", ".include \"open_if.fe\"\n.endif\n");
  try {
    fa::assemble_file(inc_if);
    ADD_FAILURE() << "no error";
  } catch (const fa::AsmError& e) {
    EXPECT_EQ(std::string(e.what()),
              open_if + ":1: .if: no .endif before the end of the file (included from " + inc_if + ":1)");
  }
  EXPECT_EQ(error_of(".include missing.fe\n"), "t.fe:1: .include: expected \"FILE\", got 'missing.fe'");
  EXPECT_EQ(error_of(".include \"\"\n"), "t.fe:1: .include: expected a file name between the quotes");
  fa::Options none;
  none.read_include = [](const std::string&, std::string&) { return false; };
  EXPECT_EQ(error_of(".include \"x.fe\"\n", none), "t.fe:1: .include: cannot read \"x.fe\"");
}

}  // namespace
