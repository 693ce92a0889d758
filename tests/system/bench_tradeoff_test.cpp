// `eskin bench tradeoff --quick` as CI runs it, and the same sweep as a
// Slurm job array on a one-node cluster this test starts itself (munged,
// slurmctld and slurmd from Debian's slurm-wlm, a generated slurm.conf and
// munge key in a temporary directory, ports of its own): the merged CSV must
// equal the local run's byte for byte.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "host/bench/text_file.h"
#include "cli_run.h"
#include "slurm_cluster.h"
#include "hls/sdft_bank_config.h"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) { return eskin::bench::read_text(p.string()); }

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("eskin_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// CSV rows keyed by their first nine columns (the point).
std::map<std::string, std::vector<std::string>> rows_by_point(const std::string& csv) {
  std::map<std::string, std::vector<std::string>> m;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream s(line);
    for (std::string x; std::getline(s, x, ',');) f.push_back(x);
    std::string key;
    for (int i = 0; i < 9; ++i) key += f[size_t(i)] + (i < 8 ? "," : "");
    m[key] = f;
  }
  return m;
}

// Column 19: amplitude error vs truth; 20: vs the golden direct DFT (% of a
// full carrier); 9, 10: the FPGA latency in clocks and us.
TEST(BenchTradeoff, QuickSweepWritesTheMapAndItsFiguresHold) {
  const fs::path out = fresh_dir("tradeoff_quick");
  const CliResult r = run_eskin("bench tradeoff --quick --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const auto rows = rows_by_point(slurp(out / "tradeoff.csv"));
  EXPECT_GE(rows.size(), 15u);
  const std::string html = slurp(out / "tradeoff.html");
  EXPECT_NE(html.find("Pareto front"), std::string::npos);
  EXPECT_NE(html.find("new Chart"), std::string::npos);

  // The FPGA's exact DFT on bin-centred carriers (no demixing) against the
  // double-precision direct DFT: within the worst-case amplitude bound of
  // its widths (hls/sdft_bank_config.h, 12-bit samples |x| <= 2048; /4 to
  // the scene's 10-bit LSB; % of the full carrier 155.15 LSB).
  // RMS <= max <= bound.
  const auto& fpga = rows.at("fpga-exact,32,16,10,0,bin,improved,35,1");
  eskin::hls::SdftWidths w;
  w.n = 32, w.xw = 12, w.cw = 16, w.tw = 10, w.acc_w = 18;
  const double bound_pct = eskin::hls::sdft_amplitude_error_bound(w, 2048) / 4 / 155.15 * 100;
  EXPECT_LE(std::stod(fpga[20]), bound_pct);
  EXPECT_GT(std::stod(fpga[20]), 0.0) << "fixed point is not exact: a zero means no comparison";
  // Thesis carriers leak into each other under a rectangular 32-sample
  // window (up to ~20%); joint least squares removes the leakage, so its
  // error against the truth is lower, on the golden model and on the
  // FPGA (which demixes them); bin-centred carriers do not leak.
  const double exact = std::stod(rows.at("golden-exact,32,16,10,0,thesis,off,35,1")[19]);
  const double ls = std::stod(rows.at("golden-ls,32,16,10,0,thesis,off,35,1")[19]);
  const double bin = std::stod(rows.at("golden-exact,32,16,10,0,bin,off,35,1")[19]);
  const auto& fpga_thesis = rows.at("fpga-exact,32,16,10,0,thesis,improved,35,1");
  EXPECT_LT(ls, exact / 5) << "cross-talk removal must cut the thesis carriers' error";
  EXPECT_LT(std::stod(fpga_thesis[19]), exact / 5) << "the top's demixing must cut it too";
  EXPECT_LT(bin, exact / 5) << "bin-centred carriers must not leak";
  // Latency: the frame engine's slowest frame fits the 1 ms frame at the
  // top's 18 MHz (17 990 clocks between frames at 35 kHz, step 35), and
  // the us column is the clocks at 18 MHz.
  const double cycles = std::stod(fpga_thesis[9]);
  EXPECT_GT(cycles, 1000.0);
  EXPECT_LT(cycles, 17990.0);
  EXPECT_NEAR(std::stod(fpga_thesis[10]), cycles / 18.0, 1e-3);
  fs::remove_all(out);
}

TEST(BenchTradeoff, SlurmJobArrayEqualsTheLocalRun) {
  const fs::path local = fresh_dir("tradeoff_local"), remote = fresh_dir("tradeoff_slurm");
  const CliResult l = run_eskin("bench tradeoff --quick --out " + local.string());
  ASSERT_EQ(l.status, 0) << l.out;
  SlurmCluster cluster(fresh_dir("slurm"));
  ASSERT_TRUE(cluster.ok()) << "the one-node Slurm cluster did not come up:\n" << cluster.logs();
  ::setenv("SLURM_CONF", cluster.conf().c_str(), 1);
  const CliResult s = run_eskin("bench tradeoff --quick --slurm --out " + remote.string());
  ::unsetenv("SLURM_CONF");
  ASSERT_EQ(s.status, 0) << s.out << "\n" << slurp(remote / "sbatch.out") << cluster.logs();
  EXPECT_NE(s.out.find("as a Slurm job array"), std::string::npos) << s.out;
  const std::string want = slurp(local / "tradeoff.csv"), got = slurp(remote / "tradeoff.csv");
  EXPECT_GT(want.size(), 1000u);
  EXPECT_EQ(got, want);
  // Every point ran as its own array task.
  size_t parts = 0;
  for (const auto& e : fs::directory_iterator(remote / "parts")) parts += e.path().extension() == ".csv";
  EXPECT_EQ(parts, rows_by_point(want).size());
  fs::remove_all(local);
  fs::remove_all(remote);
}

}  // namespace
