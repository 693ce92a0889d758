// `eskin bench latency` as CI runs it: the reference builds measured in
// Verilator against bench/baselines/latency.csv. The repository baseline
// passes exactly (no stage faster either: the stored cycles are the
// measured ones), the frame engine's instruction-set model takes the cycles
// Verilator measured; a baseline one stage faster than the measurement
// fails, naming the build, the stage and both cycle counts.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "cli_run.h"

namespace {

const std::string kBaseline = ESKIN_SOURCE_DIR "/bench/baselines/latency.csv";

// One test, so the two runs share the cached builds instead of racing to
// make them.
TEST(BenchLatency, BaselinePassesAndGrowthFailsNamingStageAndCycles) {
  const CliResult ok = run_eskin("bench latency");
  EXPECT_EQ(ok.status, 0) << ok.out;
  EXPECT_NE(ok.out.find("latency: no stage slower than"), std::string::npos) << ok.out;
  EXPECT_EQ(ok.out.find("faster than the baseline"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("one ADC sample period 28.6 us"), std::string::npos) << ok.out;
  for (const char* c : {"3x3", "10x10"})
    EXPECT_NE(ok.out.find(std::string("engine model ") + c + ": frame"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("(agrees)"), std::string::npos) << ok.out;
  EXPECT_EQ(ok.out.find("DISAGREES"), std::string::npos) << ok.out;

  std::ifstream in(kBaseline);
  std::stringstream edited;
  std::string line;
  long base = -1;
  const std::regex row("3x3,frame_engine\\.done,([0-9]+)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, row)) {
      base = std::stol(m[1]);
      line = "3x3,frame_engine.done," + std::to_string(base - 3);
    }
    edited << line << "\n";
  }
  ASSERT_GT(base, 3) << "no 3x3 frame_engine.done row in " << kBaseline;
  const auto path = std::filesystem::temp_directory_path() / "eskin_latency_baseline_edit.csv";
  std::ofstream(path) << edited.str();
  const CliResult r = run_eskin("bench latency --config 3x3 --baseline " + path.string());
  EXPECT_EQ(r.status, 1) << r.out;
  const std::string want = "LATENCY REGRESSION: 3x3 frame_engine.done: latency grew from " +
                           std::to_string(base - 3) + " to " + std::to_string(base) +
                           " cycles (+3)";
  EXPECT_NE(r.out.find(want), std::string::npos) << "want: " << want << "\n" << r.out;
  // The baseline is read, never written, without --update-baseline.
  std::ifstream back(path);
  std::stringstream after;
  after << back.rdbuf();
  EXPECT_EQ(after.str(), edited.str());
}

}  // namespace
