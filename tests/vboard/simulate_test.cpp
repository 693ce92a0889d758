// `eskin simulate` as a user runs it: a real process on a real scene file,
// the virtual board behind a real pty, the report and raw outputs on disk.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <unistd.h>

#include "run_command.h"
#include "tests/stream/process.h"

namespace {

namespace fs = std::filesystem;

using vboard_test::run;
using vboard_test::slurp;

// The default scene's skin, one 50 kPa press of taxel (1, 2): 5 ms ramp
// from 10 ms, held 20 ms.
fs::path one_press_scene(const std::string& name) {
  std::string text = slurp(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  text.replace(text.find("duration_s: 0.6"), 15, "duration_s: 0.05");
  text.erase(text.find("stimuli:"));
  text += "stimuli:\n  - press: {taxel: [1, 2], pressure_kpa: 50, t_start_s: 0.010, ramp_s: 0.005, "
          "hold_s: 0.020, release_s: 0.005}\noutputs: [amplitudes, taxels, spikes]\n";
  const fs::path p = fs::path(testing::TempDir()) / (name + ".yaml");
  std::ofstream(p) << text;
  return p;
}

// The report is one file that needs nothing else: no external script,
// style or image, the chart library inlined; it holds the run's numbers;
// the raw outputs agree with it. Bounds on the scene's one press (taxel
// r1c2, 50 kPa, g = 0.5):
//  * decoded peak pressure within 50 +- 10 kPa: the FPGA's conductance
//    taxel is sqrt(row * column amplitude); the off-bin thesis carriers
//    leak up to ~24% into their neighbours (docs/guide.md), which moves a
//    single press's line amplitudes by far less than 20%;
//  * latency from onset to the first lit frame on the host between 263 us
//    (the true g crosses the 0.05 threshold 2.63 kPa into a 5 ms ramp to
//    50 kPa) and 2377 us (that, plus one 32-sample window 914 us, one
//    taxel packet period of 35 samples 1000 us, and 200 us for the
//    pipeline and the packet's UART time).
TEST(Simulate, WritesASelfContainedReportWithTheRunsNumbers) {
  const fs::path scene = one_press_scene("sim_report");
  const fs::path out = fs::path(testing::TempDir()) / "sim_report_out";
  fs::remove_all(out);
  std::string log;
  ASSERT_EQ(run(std::string(ESKIN_BIN) + " simulate " + scene.string() + " --out " + out.string(), &log), 0)
      << log;
  EXPECT_NE(log.find("report: " + (out / "report.html").string()), std::string::npos) << log;
  const std::string html = slurp(out / "report.html");
  ASSERT_FALSE(html.empty());
  for (const char* external : {"<script src", "<link", "src=\"http", "href=\"http", "@import", "url("})
    EXPECT_EQ(html.find(external), std::string::npos) << external;
  EXPECT_NE(html.find("Chart.js v3"), std::string::npos) << "chart library not inlined";
  EXPECT_NE(html.find("new Chart("), std::string::npos);
  EXPECT_NE(html.find("canvas class=\"heatmap\""), std::string::npos);

  const auto sum = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(sum.at("fpga_build"), "default");
  EXPECT_EQ(sum.at("link_errors"), 0);
  EXPECT_NE(html.find("<td>" + std::to_string(sum.at("packets").get<int>()) + "</td>"),
            std::string::npos) << "packet count missing from the report";
  // Raw outputs: the taxel CSV has one row per taxel packet.
  std::ifstream tax(out / "fpga_taxels.csv");
  std::string line;
  std::getline(tax, line);
  ASSERT_NE(line.find("r1c2_kpa"), std::string::npos) << line;
  double peak = 0;
  int rows = 0;
  while (std::getline(tax, line)) {
    ++rows;
    std::stringstream ss(line);
    std::string cell;
    for (int col = 0; std::getline(ss, cell, ','); ++col)
      if (col == 3 + 3 * 5) peak = std::max(peak, std::stod(cell));  // r1c2_kpa: taxel 5
  }
  EXPECT_GE(rows, 45);  // 50 ms at one taxel packet per ms
  EXPECT_NEAR(peak, 50.0, 10.0);
  std::ifstream lat(out / "latency.csv");
  std::getline(lat, line);
  ASSERT_TRUE(std::getline(lat, line));
  double onset, fpga_us, golden_us;
  char name[8];
  ASSERT_EQ(std::sscanf(line.c_str(), "%7[^,],%lf,%lf,%lf", name, &onset, &fpga_us, &golden_us), 4);
  EXPECT_STREQ(name, "r1c2");
  EXPECT_GE(fpga_us, 263.0);
  EXPECT_LE(fpga_us, 2377.0);
  EXPECT_NE(html.find(std::to_string(int(fpga_us))), std::string::npos);
}

// The default scene's figures the docs cite (docs/vboard.md,
// <!--fig:vboard/NAME-->), from `eskin simulate scenes/neuroskin2.yaml` run
// as a user runs it: its summary.json, whose latency_median_us is the
// figure the command prints ("latency touch onset -> first FPGA frame on
// the host: median N us"). Simulated time, the exact RTL, a fixed scene and
// the host's commands held for (--hold-for-host-bytes): the same on every
// machine, so docs/vboard_figures.csv must equal the run's figures as
// written. ESKIN_UPDATE_FIGURES=1 writes the file instead;
// tests/system/doc_figures_test.cpp checks the docs against it.
TEST(Simulate, DefaultSceneFiguresAreTheDocs) {
  const fs::path out = fs::path(testing::TempDir()) / "sim_doc_figures_out";
  fs::remove_all(out);
  eskin::testing::Process p({ESKIN_BIN, "simulate", ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml",
                             "--out", out.string()},
                            testing::TempDir() + "sim_doc_figures.out",
                            testing::TempDir() + "sim_doc_figures.err");
  ASSERT_EQ(p.wait_exit(std::chrono::minutes(10)), 0) << p.out() << p.err();
  const auto sum = nlohmann::json::parse(slurp(out / "summary.json"));
  ASSERT_EQ(sum.at("link_errors"), 0) << "latencies need an error-free link";
  const auto fixed = [](double v, int decimals) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    return std::string(b);
  };
  struct Row {
    std::string name, value, unit;
  };
  const std::string source = "tests/vboard/simulate_test.cpp (eskin simulate scenes/neuroskin2.yaml, summary.json)";
  const std::vector<Row> run = {
      {"default.packets", std::to_string(sum.at("packets").get<long>()), "packets"},
      {"default.latency_median_us", fixed(sum.at("latency_median_us").get<double>(), 1), "us"},
      {"default.fpga_spikes", std::to_string(sum.at("fpga_spikes").get<long>()), "spikes"},
      {"default.fpga_spikes_layer2", std::to_string(sum.at("fpga_spikes_layer2").get<long>()),
       "spikes"},
      {"default.fpga_worst_rms_kpa", fixed(sum.at("fpga_worst_rms_kpa").get<double>(), 3), "kPa"},
  };
  // The command prints the latency as the file holds it, rounded.
  EXPECT_NE(p.out().find("median " + fixed(sum.at("latency_median_us").get<double>(), 0) + " us"),
            std::string::npos)
      << p.out();
  const fs::path file = ESKIN_SOURCE_DIR "/docs/vboard_figures.csv";
  if (const char* u = std::getenv("ESKIN_UPDATE_FIGURES"); u && *u && std::string(u) != "0") {
    std::ofstream f(file, std::ios::binary);
    f << "# The default scene on the virtual board, as the docs cite it\n"
         "# (<!--fig:vboard/NAME-->): written by tests/vboard/simulate_test.cpp\n"
         "# (ESKIN_UPDATE_FIGURES=1 build/bin/vboard_simulate_test\n"
         "# --gtest_filter=*DefaultSceneFiguresAreTheDocs), which fails when a run\n"
         "# differs from it; simulated time, the same on every machine.\n"
         "name,value,unit,source\n";
    for (const Row& r : run) f << r.name << ',' << r.value << ',' << r.unit << ",\"" << source << "\"\n";
    return;
  }
  std::map<std::string, std::string> have;
  std::istringstream in(slurp(file));
  std::string line;
  for (bool header = true; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    const size_t c1 = line.find(',');
    const size_t c2 = line.find(',', c1 + 1);
    have[line.substr(0, c1)] = line.substr(c1 + 1, c2 - c1 - 1);
  }
  for (const Row& r : run) {
    const auto it = have.find(r.name);
    if (it == have.end()) {
      ADD_FAILURE() << file << " lacks " << r.name << " (the run gives " << r.value
                    << "): regenerate it (ESKIN_UPDATE_FIGURES=1)";
      continue;
    }
    EXPECT_EQ(it->second, r.value) << file << ": " << r.name << " is " << it->second
                                   << ", the run gives " << r.value
                                   << " (regenerate: ESKIN_UPDATE_FIGURES=1, then fix the docs)";
  }
  EXPECT_EQ(have.size(), run.size()) << file << " has figures this run does not give";
}

// A bad scene is refused before anything runs: the error names the file
// and the field, the exit status is non-zero, and no output is written.
TEST(Simulate, BadSceneFailsBeforeRunning) {
  std::string text = slurp(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  text.replace(text.find("rows: 3"), 7, "rows: -3");
  const fs::path scene = fs::path(testing::TempDir()) / "sim_bad.yaml";
  std::ofstream(scene) << text;
  const fs::path out = fs::path(testing::TempDir()) / "sim_bad_out";
  fs::remove_all(out);
  std::string log;
  EXPECT_NE(run(std::string(ESKIN_BIN) + " simulate " + scene.string() + " --out " + out.string(), &log), 0);
  EXPECT_NE(log.find("sim_bad.yaml"), std::string::npos) << log;
  EXPECT_NE(log.find("skin.rows"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out));
}

// The build tree belongs to whoever built it (root, on a lab machine); a
// user runs the default scene's board without writing to it: the board's
// per-run microcode files go to the user's cache (sim/vboard/fpga_params.h,
// RunFiles), which is empty again after the run. As root, the run drops to
// uid/gid 65534 (nobody) with setpriv; otherwise it runs as this user. The
// default build's files in the build tree's vboard folder must not change
// (the board used to write its microcode and a lock file there, which a
// user who does not own the tree cannot).
TEST(Simulate, AUserWhoDoesNotOwnTheBuildTreeRunsTheDefaultScene) {
  const fs::path home = fs::path(testing::TempDir()) / "sim_user";
  fs::remove_all(home);
  fs::create_directories(home / "cache");
  std::vector<std::string> argv;
  if (::getuid() == 0) {
    for (const fs::path& d : {home, home / "cache"})
      ASSERT_EQ(::chown(d.c_str(), 65534, 65534), 0) << d;
    argv = {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"};
    // The tree must be readable to another user at all (a clone in a 0700
    // folder is not): that is the machine's choice, not eskin's.
    eskin::testing::Process probe(
        {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "/usr/bin/test",
         "-x", ESKIN_BIN},
        (home / "probe.out").string(), (home / "probe.err").string());
    if (probe.wait_exit(std::chrono::seconds(10)) != 0)
      GTEST_SKIP() << ESKIN_BIN << " is not reachable for uid 65534 (a parent folder is private)";
  }
  for (const std::string& a : std::vector<std::string>{"/usr/bin/env", "-i", "PATH=/usr/bin:/bin", "XDG_CACHE_HOME=" + (home / "cache").string(),
        std::string(ESKIN_BIN), "simulate", ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml", "--out",
        (home / "out").string()})
    argv.push_back(a);
  const fs::path vboard_dir = fs::path(ESKIN_BIN).parent_path().parent_path() / "vboard";
  auto listing = [&] {
    std::map<std::string, fs::file_time_type> m;
    if (fs::exists(vboard_dir))  // the default build's files (other tests add other builds)
      for (const auto& e : fs::directory_iterator(vboard_dir))
        if (e.path().filename().string().rfind("default.", 0) == 0)
          m[e.path().string()] = e.last_write_time();
    return m;
  };
  const auto before = listing();
  eskin::testing::Process sim(argv, (home / "sim.out").string(), (home / "sim.err").string());
  ASSERT_EQ(sim.wait_exit(std::chrono::seconds(300)), 0) << sim.out() << sim.err();
  // The same packets as this process's own run of the scene.
  std::string log;
  ASSERT_EQ(run(std::string(ESKIN_BIN) + " simulate " ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml --out " +
                    (home / "out_self").string(), &log), 0) << log;
  const std::string packets = slurp(home / "out/fpga_packets.ndjson");
  EXPECT_GT(packets.size(), 1000u);
  EXPECT_EQ(packets, slurp(home / "out_self/fpga_packets.ndjson"));
  EXPECT_TRUE(fs::is_empty(home / "cache/eskin/vboard")) << "the run's files were not removed";
  EXPECT_EQ(listing(), before) << vboard_dir << " changed";
}

// A scene that needs another FPGA build gets its virtual board built by
// `eskin simulate` (sim/vboard/vboard_build.h): scenes/planned3x3.yaml has
// bin-centred carriers (no demixing: 6 DFT channels, not 7) and wants no
// spikes (the microcode skips the neurons), so its build is not the
// default one. The first run in a build tree builds eskin-vboard-KEY
// (minutes), a second run finds it. Bounds: every frame on time (no frame
// overrun, no link error), no spike packet, and the FPGA's carrier
// amplitudes within 1 LSB of golden's on the same samples (the FPGA rounds
// each magnitude to a whole LSB, 0.5; its 16-bit twiddles and the DFT gain
// of 1 - 2^-15 add under 0.1 LSB at these amplitudes). Taxels are not
// bounded here: the scene's last press is a disk spread over r1c1 and
// r1c2, which the FPGA's per-line product reconstruction over-reads
// (docs/fpga.md, accuracy).
TEST(Simulate, ASceneOfAnotherBuildGetsItsBoardBuilt) {
  const fs::path out = fs::path(testing::TempDir()) / "sim_planned3x3";
  fs::remove_all(out);
  const std::string cmd = std::string(ESKIN_BIN) + " simulate " ESKIN_SOURCE_DIR
                          "/scenes/planned3x3.yaml --out " + out.string();
  std::string log;
  ASSERT_EQ(run(cmd, &log), 0) << log;
  const nlohmann::json sum = nlohmann::json::parse(slurp(out / "summary.json"));
  const std::string key = sum.at("fpga_build");
  ASSERT_EQ(key.rfind("p", 0), 0u) << key;
  EXPECT_TRUE(fs::exists(fs::path(ESKIN_VBOARD_BIN).parent_path() / ("eskin-vboard-" + key)));
  EXPECT_GT(sum.at("packets").get<int>(), 100);
  EXPECT_EQ(sum.at("link_errors").get<int>(), 0);
  EXPECT_GT(sum.at("status_packets").get<int>(), 0);
  EXPECT_EQ(sum.at("frame_overruns").get<int>(), 0);
  EXPECT_EQ(sum.at("fpga_spikes").get<int>(), 0);
  EXPECT_LT(sum.at("fpga_vs_golden_max_amp_lsb").get<double>(), 1.0);
  // The second run uses the board the first one built.
  ASSERT_EQ(run(cmd, &log), 0) << log;
  EXPECT_EQ(log.find("building the virtual board"), std::string::npos) << log;
}

// The virtual board builds the frame engine `eskin bitstream` chooses for
// the iCEBreaker, not only its clock. scenes/staggered10x10.yaml (20
// carriers at 70 kS/s, a 1 ms frame) needs more than 18 MHz with the
// board's own engine (bit-serial, neurons in microcode: its longest frame
// 52 915 clocks) and with the barrel shifter alone (33 144); with the
// bit-serial shifter and the neuron unit its measured frames fit (13 466)
// but its static bound does not fit 90 % of the frame, so the board takes
// barrel + unit, the next, and keeps 18 MHz (host/fpga/flow.h;
// tests/fpga/bitstream_flow_test.cpp). Bounds: no frame
// overrun and no dropped packet, which needs an engine that keeps up;
// FPGA and golden spike counts equal (the golden model steps the neurons
// on the FPGA's frames, so a lost frame shows as a different count).
// Negative control, before the board carried the engine: the same run
// built the bit-serial engine at 36 MHz, lost a frame and fired 13 spikes
// to golden's 12.
TEST(Simulate, TheBoardBuildsTheEngineTheFlowChose) {
  const fs::path out = fs::path(testing::TempDir()) / "sim_staggered10x10";
  fs::remove_all(out);
  std::string log;
  ASSERT_EQ(run(std::string(ESKIN_BIN) + " simulate " ESKIN_SOURCE_DIR
                "/scenes/staggered10x10.yaml --out " + out.string(), &log), 0) << log;
  const nlohmann::json sum = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(sum.at("fpga_engine_shifter"), "barrel");
  EXPECT_EQ(sum.at("fpga_neurons"), "unit");
  EXPECT_EQ(sum.at("fpga_clk_hz").get<double>(), 18e6);
  EXPECT_EQ(sum.at("frame_overruns").get<int>(), 0);
  EXPECT_EQ(sum.at("dropped_packets").get<int>(), 0);
  EXPECT_EQ(sum.at("link_errors").get<int>(), 0);
  EXPECT_GT(sum.at("status_packets").get<int>(), 0);
  EXPECT_GT(sum.at("golden_spikes").get<int>(), 0);
  EXPECT_EQ(sum.at("fpga_spikes"), sum.at("golden_spikes"));
  EXPECT_EQ(sum.at("fpga_spikes_layer2"), sum.at("golden_spikes_layer2"));
  const std::string html = slurp(out / "report.html");
  EXPECT_NE(html.find("barrel shifter, neurons on the neuron unit"), std::string::npos);
}

// --trace writes an FST waveform that GTKWave's fst2vcd reads, with the
// FPGA's pins toggling.
TEST(Simulate, TraceWritesAnFstWaveform) {
  const fs::path scene = one_press_scene("sim_trace");
  std::string text = slurp(scene);
  text.replace(text.find("duration_s: 0.05"), 16, "duration_s: 0.04");
  std::ofstream(scene) << text;
  const fs::path out = fs::path(testing::TempDir()) / "sim_trace_out";
  const fs::path fst = out / "fpga.fst";
  fs::remove_all(out);
  std::string log;
  ASSERT_EQ(run(std::string(ESKIN_BIN) + " simulate " + scene.string() + " --out " + out.string() +
                    " --trace " + fst.string(), &log), 0) << log;
  ASSERT_GT(fs::file_size(fst), 1000u);
  std::string vcd;
  ASSERT_EQ(run("fst2vcd " + fst.string() + " | head -c 2000000", &vcd), 0);
  for (const char* sig : {"uart_txd", "adc_sclk", "adc_cs_n", "clk"})
    EXPECT_NE(vcd.find(std::string(" ") + sig + " "), std::string::npos) << sig;
  EXPECT_NE(vcd.find("#"), std::string::npos) << "no time steps";
}

}  // namespace
