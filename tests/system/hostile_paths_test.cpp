// Paths a shell would read as code, given to every eskin subcommand that
// starts a process: a single and a double quote, $(...), backticks, ';',
// spaces and a leading '-'. Each canary command in them would create a
// file named eskin_canary_PID_N; none may exist after the run, anywhere
// under the test's folder (each eskin runs there) or in /tmp. The command
// either works with that path (its outputs there, computed) or fails
// naming it; never exit 0 with results it did not compute.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_argv.h"
#include "host/bench/text_file.h"
#include "host/bench/tradeoff.h"
#include "slurm_cluster.h"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) { return eskin::bench::read_text(p.string()); }

std::string canary(int n) { return "eskin_canary_" + std::to_string(::getpid()) + "_" + std::to_string(n); }

// One folder name with every canary: a shell that sees it (quoted with
// '...', "..." or not at all) runs at least one of them.
std::string hostile_name(bool with_double_quote) {
  return "-it's " + std::string(with_double_quote ? "\"q\" " : "") + "$(touch " + canary(1) +
         ") `touch " + canary(2) + "`; touch " + canary(3) + "; '; touch " + canary(4) +
         "; echo ' sp ace";
}

// The test's folder, where each eskin runs (a relative canary lands here).
fs::path work_dir() {
  static const fs::path d = [] {
    const fs::path p = fs::temp_directory_path() / ("eskin_hostile_" + std::to_string(::getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
  }();
  return d;
}

// Every canary file found under the test's folder, in /tmp or in the
// source tree's root (a shell's cwd could be any of them).
std::vector<std::string> canaries_found() {
  std::vector<std::string> found;
  const std::string prefix = "eskin_canary_" + std::to_string(::getpid()) + "_";
  for (const auto& e : fs::recursive_directory_iterator(work_dir()))
    if (e.path().filename().string().rfind(prefix, 0) == 0) found.push_back(e.path().string());
  for (const fs::path& dir : {fs::path("/tmp"), fs::path(ESKIN_SOURCE_DIR), fs::current_path()})
    for (int n = 1; n <= 4; ++n)
      if (fs::exists(dir / canary(n))) found.push_back((dir / canary(n)).string());
  return found;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x + "\n";
  return s;
}

#define EXPECT_NO_CANARY() EXPECT_TRUE(canaries_found().empty()) << "an injected command ran:\n" << joined(canaries_found())

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST(HostilePaths, UcodeAsmWritesToTheHostilePath) {
  const fs::path dir = work_dir() / "ucode" / hostile_name(true);
  fs::create_directories(dir);
  std::ofstream(dir / "p.fe") << "        ld 7\nhalt:   j halt\n";
  const ArgvResult r = run_eskin_argv({"ucode", "asm", (dir / "p.fe").string(), "-o", (dir / "p.hex").string()},
                                      work_dir().string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(slurp(dir / "p.hex"), "40000007\nc0000001\n");
  EXPECT_NO_CANARY();
}

// The image goes to the current directory by default, never beside the
// source (which may be a tree the user does not mean to write).
TEST(HostilePaths, UcodeAsmDefaultsToTheCurrentDirectory) {
  const fs::path src = work_dir() / "ucode_src", cwd = work_dir() / "ucode_cwd";
  fs::create_directories(src);
  fs::create_directories(cwd);
  std::ofstream(src / "prog.fe") << "        ld 7\nhalt:   j halt\n";
  const ArgvResult r = run_eskin_argv({"ucode", "asm", (src / "prog.fe").string()}, cwd.string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_FALSE(fs::exists(src / "prog.hex")) << "written beside the source";
  EXPECT_EQ(slurp(cwd / "prog.hex"), "40000007\nc0000001\n") << r.out;
  EXPECT_NE(r.out.find("-> prog.hex"), std::string::npos) << r.out;
}

TEST(HostilePaths, BenchTradeoffOut) {
  const fs::path out = work_dir() / "tradeoff" / hostile_name(true);
  const auto t0 = std::chrono::steady_clock::now();
  const ArgvResult r = run_eskin_argv({"bench", "tradeoff", "--quick", "--out=" + out.string()},
                                      work_dir().string());
  std::cout << "bench tradeoff --quick: " << seconds_since(t0) << " s\n";
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_GT(slurp(out / "tradeoff.csv").size(), 1000u);
  EXPECT_NE(slurp(out / "tradeoff.html").find("Pareto front"), std::string::npos);
  EXPECT_NO_CANARY();
}

// --synth with a table of every build the quick sweep has but one (the
// keys from eskin's own synth_key: inputs, not expected values; their
// cells are placeholders): that one build is synthesised with Yosys into
// the hostile cache, once. Its rows must say "synth" with the cells Yosys
// counted (not a placeholder), and the cache hold its stat.txt.
TEST(HostilePaths, BenchTradeoffSynthCache) {
  const fs::path base = work_dir() / "synth" / hostile_name(false);
  fs::create_directories(base);
  std::string dropped, line;
  {
    std::ofstream t(base / "table.csv");
    t << "key,luts,dsp,bram,spram\n";
    for (const auto& p : eskin::bench::tradeoff_points(true)) {
      const std::string key = eskin::bench::synth_key(p);
      if (key.empty()) continue;
      if (dropped.empty()) dropped = key;
      if (key != dropped) t << key << ",1,0,0,0\n";
    }
  }
  ASSERT_FALSE(dropped.empty()) << "no point of the quick sweep has an RTL build";
  const fs::path cache = base / "cache", out = base / "out";
  const auto t0 = std::chrono::steady_clock::now();
  const ArgvResult r = run_eskin_argv({"bench", "tradeoff", "--quick", "--synth", "--synth-cache",
                                       cache.string(), "--synth-table", (base / "table.csv").string(),
                                       "--out", out.string()},
                                      work_dir().string());
  std::cout << "bench tradeoff --quick --synth (one build): " << seconds_since(t0) << " s\n";
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NO_CANARY();
  const std::string stat = slurp(cache / dropped / "stat.txt");
  EXPECT_NE(stat.find("SB_LUT4"), std::string::npos) << "Yosys did not run for " << dropped;
  // The rows of the dropped build took their resources from this run's
  // synthesis; the others from the table.
  std::istringstream csv(slurp(out / "tradeoff.csv"));
  int synthesised = 0;
  std::getline(csv, line);  // header
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::istringstream s(line);
    for (std::string x; std::getline(s, x, ',');) f.push_back(x);
    ASSERT_GT(f.size(), 18u) << line;
    if (f[18] == "synth") {
      ++synthesised;
      EXPECT_GT(std::stol(f[14]), 1) << "LUT4s from Yosys, not the table's placeholder: " << line;
    }
  }
  EXPECT_GT(synthesised, 0) << slurp(out / "tradeoff.csv");
}

// The same sweep as a Slurm job array on a one-node cluster: the job
// script, its arguments and the parts all under the hostile --out.
TEST(HostilePaths, BenchTradeoffSlurmOut) {
  if (::geteuid() != 0) GTEST_SKIP() << "the one-node cluster's daemons run as root";
  SlurmCluster cluster(work_dir() / "slurm");
  ASSERT_TRUE(cluster.ok()) << "the one-node Slurm cluster did not come up:\n" << cluster.logs();
  ::setenv("SLURM_CONF", cluster.conf().c_str(), 1);
  const fs::path out = work_dir() / "tradeoff_slurm" / hostile_name(true);
  const auto t0 = std::chrono::steady_clock::now();
  const ArgvResult r = run_eskin_argv({"bench", "tradeoff", "--quick", "--slurm", "--out=" + out.string()},
                                      work_dir().string());
  std::cout << "bench tradeoff --quick --slurm: " << seconds_since(t0) << " s\n";
  ::unsetenv("SLURM_CONF");
  EXPECT_NO_CANARY();
  ASSERT_EQ(r.status, 0) << r.out << "\n" << slurp(out / "sbatch.out") << cluster.logs();
  EXPECT_NE(r.out.find("as a Slurm job array"), std::string::npos) << r.out;
  EXPECT_GT(slurp(out / "tradeoff.csv").size(), 1000u);
  EXPECT_TRUE(fs::exists(out / "parts" / "0.csv"));
}

// The latency bench's Verilator build and harness run with the hostile
// --cache (the Hall build: the smallest); GNU Make cannot build in such a
// folder, so the build is made elsewhere and moved in: the harness must be
// there and the run must pass against the baseline.
TEST(HostilePaths, BenchLatencyCache) {
  const fs::path cache = work_dir() / "latency" / hostile_name(true);
  const auto t0 = std::chrono::steady_clock::now();
  const ArgvResult r = run_eskin_argv({"bench", "latency", "--config", "hall000", "--cache=" + cache.string()},
                                      work_dir().string());
  std::cout << "bench latency --config hall000 (fresh cache): " << seconds_since(t0) << " s\n";
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("latency: no stage slower than"), std::string::npos) << r.out;
  bool harness = false;
  for (const auto& e : fs::recursive_directory_iterator(cache))
    harness = harness || e.path().filename() == "hall_latency_harness";
  EXPECT_TRUE(harness) << "no harness built in " << cache;
  EXPECT_NO_CANARY();
}

// A double quote cannot go into the core's Verilog strings or Yosys's
// script: refused before anything runs, naming the path (exit 2).
TEST(HostilePaths, BitstreamRefusesADoubleQuoteNamingThePath) {
  const fs::path out = work_dir() / "bitstream" / hostile_name(true);
  const ArgvResult r = run_eskin_argv({"bitstream", "--board", "icebreaker", "--out=" + out.string()},
                                      work_dir().string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(out.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("double quote"), std::string::npos) << r.out;
  EXPECT_NO_CANARY();
}

// The default scene's skin for 50 ms, one press (as tests/vboard/simulate_test.cpp).
fs::path short_scene() {
  std::string text = slurp(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  text.replace(text.find("duration_s: 0.6"), 15, "duration_s: 0.05");
  text.erase(text.find("stimuli:"));
  text += "stimuli:\n  - press: {taxel: [1, 2], pressure_kpa: 50, t_start_s: 0.010, ramp_s: 0.005, "
          "hold_s: 0.020, release_s: 0.005}\noutputs: [amplitudes, taxels, spikes]\n";
  const fs::path p = work_dir() / "short.yaml";
  std::ofstream(p) << text;
  return p;
}

TEST(HostilePaths, SimulateOut) {
  const fs::path out = work_dir() / "simulate" / hostile_name(true);
  const auto t0 = std::chrono::steady_clock::now();
  const ArgvResult r = run_eskin_argv({"simulate", short_scene().string(), "--out=" + out.string()},
                                      work_dir().string());
  std::cout << "simulate (50 ms): " << seconds_since(t0) << " s\n";
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NO_CANARY();
  bool html = false;
  for (const auto& e : fs::directory_iterator(out)) html = html || e.path().extension() == ".html";
  EXPECT_TRUE(html) << "no report in " << out;
}

// An --out that cannot be a folder (under a regular file: refused for root
// too) is named at once, before the board is built or run.
TEST(HostilePaths, SimulateUnwritableOutFailsBeforeRunning) {
  const fs::path file = work_dir() / "a_file";
  std::ofstream(file) << "x";
  const fs::path out = file / "sub";
  const auto t0 = std::chrono::steady_clock::now();
  const ArgvResult r = run_eskin_argv({"simulate", short_scene().string(), "--out", out.string()},
                                      work_dir().string());
  const double s = seconds_since(t0);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find(out.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cannot create the output folder"), std::string::npos) << r.out;
  EXPECT_LT(s, 5.0) << "found only after running: " << r.out;
}

// A folder that exists but takes no file: mode 0500 for a user who is not
// root; for root (whom modes do not stop) /proc/1, where no one creates
// files. Named before anything runs (the report's write came last).
TEST(HostilePaths, SimulateReadOnlyOutFailsBeforeRunning) {
  fs::path out = "/proc/1";
  if (::geteuid() != 0) {
    out = work_dir() / "read_only";
    fs::create_directories(out);
    ::chmod(out.c_str(), 0500);
  }
  const ArgvResult r = run_eskin_argv({"simulate", short_scene().string(), "--out", out.string()},
                                      work_dir().string());
  if (::geteuid() != 0) ::chmod(out.c_str(), 0700);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("'" + out.string() + "': cannot write in the output folder"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("board"), std::string::npos) << "the board ran first: " << r.out;
}

}  // namespace
