// `eskin bench latency --ci` as CI runs it: the reference builds CI measures
// (3x3, 10x10, the seed-000 Hall top; 16x16 only in the full run) in
// Verilator against bench/baselines/latency.csv. The repository baseline
// passes exactly (no stage faster either: the stored cycles are the
// measured ones), the frame engine's instruction-set model takes the cycles
// Verilator measured; a baseline one stage faster than the measurement
// fails, naming the build, the stage and both cycle counts, for the DTMF
// and the Hall top.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>

#include "cli_run.h"

namespace {

const std::string kBaseline = ESKIN_SOURCE_DIR "/bench/baselines/latency.csv";

// The baseline with one row's cycles lowered by `minus`; returns the
// edited file's path and the row's stored cycles in `base`.
std::string lowered_baseline(const std::string& config, const std::string& stage, long minus,
                             long& base, std::string& text) {
  std::ifstream in(kBaseline);
  std::stringstream edited;
  std::string line;
  base = -1;
  const std::string prefix = config + "," + stage + ",";
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) {
      base = std::stol(line.substr(prefix.size()));
      line = prefix + std::to_string(base - minus);
    }
    edited << line << "\n";
  }
  text = edited.str();
  const auto path = std::filesystem::temp_directory_path() /
                    ("eskin_latency_baseline_" + config + ".csv");
  std::ofstream(path) << text;
  return path.string();
}

// One test, so the runs share the cached builds instead of racing to make
// them.
TEST(BenchLatency, BaselinePassesAndGrowthFailsNamingStageAndCycles) {
  const CliResult ok = run_eskin("bench latency --ci");
  EXPECT_EQ(ok.status, 0) << ok.out;
  EXPECT_NE(ok.out.find("latency: no stage slower than"), std::string::npos) << ok.out;
  EXPECT_EQ(ok.out.find("faster than the baseline"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("one ADC sample period 28.6 us"), std::string::npos) << ok.out;
  for (const char* c : {"3x3", "10x10"})
    EXPECT_NE(ok.out.find(std::string("engine model ") + c + ": frame"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("(agrees)"), std::string::npos) << ok.out;
  EXPECT_EQ(ok.out.find("DISAGREES"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("hall000: "), std::string::npos) << ok.out;
  EXPECT_EQ(ok.out.find("latency 16x16"), std::string::npos) << "16x16 is not a CI build\n" << ok.out;

  for (const auto& [config, stage, minus] :
       {std::tuple<std::string, std::string, long>{"3x3", "frame_engine.done", 3},
        {"hall000", "uart.last_stop_bit", 1}}) {
    long base = 0;
    std::string text;
    const std::string path = lowered_baseline(config, stage, minus, base, text);
    ASSERT_GT(base, minus) << "no " << config << " " << stage << " row in " << kBaseline;
    const CliResult r = run_eskin("bench latency --config " + config + " --baseline " + path);
    EXPECT_EQ(r.status, 1) << r.out;
    const std::string want = "LATENCY REGRESSION: " + config + " " + stage +
                             ": latency grew from " + std::to_string(base - minus) + " to " +
                             std::to_string(base) + " cycles (+" + std::to_string(minus) + ")";
    EXPECT_NE(r.out.find(want), std::string::npos) << "want: " << want << "\n" << r.out;
    // The baseline is read, never written, without --update-baseline.
    std::ifstream back(path);
    std::stringstream after;
    after << back.rdbuf();
    EXPECT_EQ(after.str(), text);
  }
}

}  // namespace
