// `eskin bench stability` on a short run (the full one is a benchmark:
// docs/bench.md): the exact sliding DFT equals the direct sum at every
// checkpoint (bound: 0 LSB, integer arithmetic on both sides), the naive
// double recursion has left the direct DFT by then (its rounding error is
// > 0 after 10^5 samples; it only grows), both neuron layers of the top's
// plan stay in range at their input extremes and answer afterwards as a
// fresh neuron does. The command's exit code carries all of it.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "cli_run.h"

TEST(BenchStability, ShortRunIsBitExactAndNeuronsRecover) {
  const std::string out =
      (std::filesystem::temp_directory_path() / "eskin_bench_stability.html").string();
  const CliResult r =
      run_eskin("bench stability --samples 1e5 --neuron-steps 1e4 --checkpoints 8 --out " + out);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("exact: 0 LSB from the direct sum over 100000 samples (bit-exact)"),
            std::string::npos) << r.out;
  // The last checkpoint's row: sample 100000, exact 0, naive > 0.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("\\n\\s+100000\\s+0\\s+(\\S+)\\s+\\S+\\n")))
      << r.out;
  EXPECT_GT(std::stod(m[1]), 0.0) << r.out;
  for (const char* layer : {"layer 1: ", "layer 2: "})
    EXPECT_NE(r.out.find(std::string(layer) + "max gain, J = +512 mV/step"), std::string::npos)
        << r.out;
  EXPECT_EQ(r.out.find("in range: NO"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("recovery (same spikes and state as a fresh neuron): yes"),
            std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(out));
  std::filesystem::remove(out);
}

// A scene that does not load is named before anything runs.
TEST(BenchStability, BadSceneFailsNamingTheFile) {
  const CliResult r = run_eskin("bench stability --samples 100 --scene /nonexistent/skin.yaml");
  EXPECT_NE(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("/nonexistent/skin.yaml"), std::string::npos) << r.out;
}
