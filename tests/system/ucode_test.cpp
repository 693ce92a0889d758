// `eskin ucode asm|run|build` as a user runs them: real processes and files. The
// expected words are packed by hand from docs/frame_engine.md's encoding
// table; the expected register values are worked out here from the program.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

using Result = CliResult;
Result sh(const std::string& args) { return run_eskin(args); }

fs::path dir() {
  const fs::path d = fs::temp_directory_path() / ("eskin_ucode_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }
std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Sum of KROM words 1..COUNT, stored, sent to io[PORT], then halt.
const char* const kSumProgram =
    "        ldx  x1, COUNT\n"
    "        ld   0\n"
    "loop:   add  k[x1]\n"
    "        djnz x1, loop\n"
    "        st   [3]\n"
    "        out  io[PORT]\n"
    "halt:   j    halt\n";

TEST(Ucode, AsmWritesTheImageAndListing) {
  const fs::path d = dir();
  write(d / "sum.fe", kSumProgram);
  const Result r = sh("ucode asm " + (d / "sum.fe").string() + " -D COUNT=3 -D PORT=0x20 -o " +
                      (d / "sum.hex").string() + " --list " +
                      (d / "sum.lst").string());
  ASSERT_EQ(r.status, 0) << r.out;
  // ldx x1,3 | ld 0 | add k[0 + x1] | djnz x1,2 | st [3] | out io[0x20] | j 6
  EXPECT_EQ(read(d / "sum.hex"),
            "dc400003\n40000000\n05400000\nc4400002\n34000003\n3a000020\nc0000006\n");
  const std::string lst = read(d / "sum.lst");
  EXPECT_NE(lst.find("0002  05400000      3  loop:   add  k[x1]"), std::string::npos) << lst;
  EXPECT_NE(lst.find("  halt "), std::string::npos) << lst;
  EXPECT_NE(r.out.find("7 words"), std::string::npos) << r.out;
}

TEST(Ucode, RunTracesAndHaltsWithTheSum) {
  const fs::path d = dir();
  write(d / "sum.fe", kSumProgram);
  write(d / "k.hex", "00000000\n0000000a\n00000014\n0000001e\n");  // 0, 10, 20, 30
  const Result r = sh("ucode run " + (d / "sum.fe").string() + " -D COUNT=3 -D PORT=32 --krom " +
                      (d / "k.hex").string() + " --trace");
  ASSERT_EQ(r.status, 0) << r.out;
  // 1 + 1 + 3 * 2 + 1 + 1 instructions before the halting jump: the first
  // takes cycle A (clock 0) and B (clock 1), each later one a B clock (its
  // cycle A runs in the B clock before; no bubble in this program), so
  // `out` is in clock 10; the jump to itself is the 11th, in clock 11.
  EXPECT_NE(r.out.find("io[0x0020] <= 0x0000003c (60) at clock 10"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("halted at 6: jump to itself; 11 instructions, 12 clocks; A=60"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("djnz x1, 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[3]<=0x0000003c"), std::string::npos) << r.out;
}

TEST(Ucode, RunStopsAtAWaitUnlessItsEventsAreRaised) {
  const fs::path d = dir();
  write(d / "w.fe", "        wait 0x4\n        ld 7\nhalt:   j halt\n");
  Result r = sh("ucode run " + (d / "w.fe").string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("stopped at 0: wait 0x4, and --events is 0x0; 0 instructions"), std::string::npos)
      << r.out;
  r = sh("ucode run " + (d / "w.fe").string() + " --events 6");
  ASSERT_EQ(r.status, 0) << r.out;
  // wait: A in clock 0, its event in B clock 1; ld 7: no overlap after a
  // wait, so A 2 and B 3; the jump: B 4.
  EXPECT_NE(r.out.find("halted at 2: jump to itself; 3 instructions, 5 clocks; A=7"), std::string::npos)
      << r.out;
}

// `.include` reads from disk, relative to the including file (not the
// working directory): a macro from lib/, expanded in the program.
TEST(Ucode, AsmReadsIncludedFilesBesideTheSource) {
  const fs::path d = dir() / "inc";
  fs::create_directories(d / "lib");
  write(d / "lib" / "sum.fe",
        "        .macro SUM3 u, v, w\n"
        "        ld    \\u\n"
        "        add   \\v\n"
        "        add   \\w\n"
        "        .endm\n");
  write(d / "prog.fe",
        "        .include \"lib/sum.fe\"\n"
        "        SUM3  1, 2, 3\n"
        "halt:   j     halt\n");
  Result r = sh("ucode asm " + (d / "prog.fe").string() + " -o " + (d / "prog.hex").string());
  ASSERT_EQ(r.status, 0) << r.out;
  // ld 1 | add 2 | add 3 | j 3
  EXPECT_EQ(read(d / "prog.hex"), "40000001\n44000002\n44000003\nc0000003\n");
  write(d / "bad.fe", "        nop\n        .include \"lib/none.fe\"\n");
  r = sh("ucode asm " + (d / "bad.fe").string() + " -o " + (d / "bad.hex").string());
  EXPECT_EQ(r.status, 2) << r.out;  // usage: the input is wrong
  EXPECT_NE(r.out.find((d / "bad.fe").string() + ":2: .include: cannot read \"" + (d / "lib/none.fe").string() +
                       "\""),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(d / "bad.hex"));
}

TEST(Ucode, BadInputFailsNamingFileLineAndWhatWasExpected) {
  const fs::path d = dir();
  write(d / "bad.fe", "        nop\n        ld.x [1]\n");
  Result r = sh("ucode asm " + (d / "bad.fe").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("bad.fe:2: ld: field: expected one of .w .wu .l .lu .h .l15 .h15 .b, got .x"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(d / "bad.hex"));
  write(d / "undef.fe", "        ld [NOPE]\n");
  r = sh("ucode run " + (d / "undef.fe").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("undef.fe:1: ld: address: undefined symbol 'NOPE'"), std::string::npos) << r.out;
  r = sh("ucode asm " + (d / "undef.fe").string() + " -D NOPE");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("-D: expected NAME=VALUE, got 'NOPE'"), std::string::npos) << r.out;
  r = sh("ucode asm " + (d / "undef.fe").string() + " -D NOPE=1+");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("expected a value"), std::string::npos) << r.out;
  r = sh("ucode asm " + (d / "missing.fe").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("missing.fe: cannot read the file"), std::string::npos) << r.out;
  write(d / "k.hex", "0000000z\n");
  write(d / "ok.fe", "halt: j halt\n");
  r = sh("ucode run " + (d / "ok.fe").string() + " --krom " + (d / "k.hex").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("k.hex:1: expected a hex word of at most 8 digits, got '0000000z'"), std::string::npos)
      << r.out;
  r = sh("ucode asm " + (d / "ok.fe").string() + " --iw 13");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("--iw: expected 4..12, got 13"), std::string::npos) << r.out;
  fs::remove_all(d);
}

// `eskin ucode build`: the DTMF top's build of a scene. The expected
// parameters follow from the scene and docs/fpga.md, not from the code:
// neuroskin2 has 3 + 3 carriers off bin centres (demixing adds the DC
// channel: KS = 7), 35 kHz sampling and 1 ms frames (STEP = 35), and the
// UP5K's clock is 12 MHz x 3/2.
TEST(Ucode, BuildWritesTheScenesImagesAndPrintsTheTopsParameters) {
  const fs::path d = dir() / "build";
  const std::string scene = ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml";
  Result r = sh("ucode build " + scene + " --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* kv : {"CLK_HZ=18000000\n", "KS=7\n", "N=32\n", "STEP=35\n", "SAMPLE_HZ=35000\n"})
    EXPECT_NE(r.out.find(kv), std::string::npos) << kv << " in\n" << r.out;
  const fs::path ucode = d / "neuroskin2.ucode.hex", krom = d / "neuroskin2.krom.hex";
  EXPECT_NE(r.out.find("UCODE_HEX=\"" + ucode.string() + "\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("KROM_HEX=\"" + krom.string() + "\""), std::string::npos) << r.out;
  // Both images are $readmemh files of 32-bit words, one per line.
  for (const fs::path& f : {ucode, krom}) {
    std::istringstream in(read(f));
    std::string line;
    int words = 0;
    while (std::getline(in, line)) {
      ASSERT_EQ(line.size(), 8u) << f << ":" << words + 1;
      ASSERT_EQ(line.find_first_not_of("0123456789abcdef"), std::string::npos) << f << ":" << words + 1;
      ++words;
    }
    EXPECT_GT(words, 100) << f;
  }
  r = sh("ucode build " + scene + " --out " + d.string() + " --clk-mhz 96");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("CLK_HZ=96000000\n"), std::string::npos) << r.out;
  write(d / "bad.yaml", "skin: {rows: x}\n");
  r = sh("ucode build " + (d / "bad.yaml").string() + " --out " + d.string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("bad.yaml:"), std::string::npos) << r.out;
  fs::remove_all(d.parent_path());
}

}  // namespace

// `eskin ucode io-map` writes the IO map's include into the source tree it
// is pointed at (ESKIN_SOURCE_DIR, common/eskin/source_tree.h), not the
// one it was built from, and what it writes is the tree's include.
TEST(Ucode, IoMapWritesTheIncludeOfTheTreeItIsPointedAt) {
  const fs::path tree = dir() / "tree";
  fs::create_directories(tree / "rtl");
  ::setenv("ESKIN_SOURCE_DIR", tree.c_str(), 1);
  const CliResult r = run_eskin("ucode io-map");
  ::unsetenv("ESKIN_SOURCE_DIR");
  ASSERT_EQ(r.status, 0) << r.out;
  const fs::path out = tree / "rtl/dtmf_io_map.vh";
  EXPECT_NE(r.out.find(out.string()), std::string::npos) << r.out;
  EXPECT_EQ(read(out), read(fs::path(ESKIN_SOURCE_DIR) / "rtl/dtmf_io_map.vh"));
}
