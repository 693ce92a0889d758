// The fidelity levels of `eskin simulate` against each other, on the
// example scenes the virtual board runs (docs/vboard.md, "Fidelity
// levels"): the cycle level (sim/cycle/dtmf_top.h) must give the Verilated
// board's host-side record exactly (every packet's bytes and its arrival
// to the nanosecond: the same bytes at the same clocks), with line and
// board faults too; the packet level (host/simulate/packet_board.h) must
// deliver the Verilated board's packets, byte for byte, each arriving
// within a bound derived here from the build, not from the model's own
// figures.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "ucode/dtmf_frame_bound.h"

namespace fs = std::filesystem;
using vboard_test::run_argv;
using vboard_test::slurp;

namespace {

struct LinkPacket {
  int seq = 0, type = 0;
  uint64_t t = 0;
  double arrival_us = 0;
  std::string payload;  // hex
};

std::vector<LinkPacket> read_link_log(const fs::path& p) {
  std::istringstream in(slurp(p));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "seq,type,t,arrival_us,payload_hex") << p;
  std::vector<LinkPacket> v;
  while (std::getline(in, line)) {
    LinkPacket k;
    std::istringstream f(line);
    std::string cell;
    std::getline(f, cell, ','), k.seq = std::stoi(cell);
    std::getline(f, cell, ','), k.type = std::stoi(cell);
    std::getline(f, cell, ','), k.t = std::stoull(cell);
    std::getline(f, cell, ','), k.arrival_us = std::stod(cell);
    std::getline(f, k.payload);
    v.push_back(k);
  }
  return v;
}

struct LevelRun {
  nlohmann::json summary;
  std::vector<LinkPacket> link;
  std::string link_text;  // fpga_link.csv as written
};

LevelRun simulate(const std::string& scene, const std::string& level,
             const std::vector<std::string>& extra = {}) {
  const fs::path out = fs::path(testing::TempDir()) / ("fidelity_" + scene + "_" + level +
                                                       std::to_string(extra.size()));
  fs::remove_all(out);
  std::string log;
  std::vector<std::string> argv{ESKIN_BIN, "simulate",
                                std::string(ESKIN_SOURCE_DIR) + "/scenes/" + scene + ".yaml",
                                "--fidelity", level, "--out", out.string()};
  argv.insert(argv.end(), extra.begin(), extra.end());
  const int rc = run_argv(argv, &log);
  EXPECT_EQ(rc, 0) << log;
  LevelRun r;
  if (rc != 0) return r;
  EXPECT_NE(log.find(level + " level"), std::string::npos) << log;
  r.summary = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(r.summary.at("fidelity"), level);
  r.link = read_link_log(out / "fpga_link.csv");
  r.link_text = slurp(out / "fpga_link.csv");
  return r;
}

// The cycle level against the RTL's run: the host's whole record equal,
// byte for byte (seq, type, t, arrival in us to 2 decimals, payload), and
// the board's figures that do not measure the simulator itself.
void expect_same_record(const std::string& scene, const LevelRun& rtl, const LevelRun& cyc) {
  ASSERT_FALSE(rtl.link.empty()) << scene;
  EXPECT_EQ(cyc.link_text, rtl.link_text) << scene << ": the cycle level's fpga_link.csv differs";
  for (const char* key : {"cycles", "sim_s", "packets", "status_packets", "dropped_packets",
                          "link_errors", "fpga_spikes", "fpga_spikes_layer2", "frame_overruns",
                          "adc_overruns"})
    EXPECT_EQ(cyc.summary.at(key), rtl.summary.at(key)) << scene << ": " << key;
  std::printf("%s: cycle level = rtl level, %zu packets and their arrivals; %.2f vs %.2f simulated s "
              "per CPU s\n",
              scene.c_str(), rtl.link.size(),
              cyc.summary.at("sim_s").get<double>() / cyc.summary.at("cpu_s").get<double>(),
              rtl.summary.at("sim_s").get<double>() / rtl.summary.at("cpu_s").get<double>());
}

constexpr int kStatusType = 0x05;
constexpr size_t kStatusSamplesHex = 2 * 24;  // STATUS's samples u32 at byte 24 (docs/protocol.md)

// The packet level's arrival error bound for the scene's build, in clocks:
// the RTL writes a frame's packets in [pending, pending + B] (B the static
// frame + command bound), the model at pending + B/2 with pending placed
// within one sample period P; the UART's departures are a max-plus function
// of the writes (no departure moves more than the largest write move); the
// framer and the USB bridge's byte sampling add at most one byte time each.
// So |arrival - arrival_rtl| <= P + B/2 + 2 bytes (+1 clock of rounding).
struct Bound {
  double clocks = 0, clk_hz = 0;
  uint64_t period = 0;
  double us() const { return clocks / clk_hz * 1e6; }
};

Bound arrival_bound(const std::string& scene_name, const nlohmann::json& sum) {
  const eskin::sim::Scene scene =
      eskin::sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/" + scene_name + ".yaml");
  const double clk = sum.at("fpga_clk_hz");
  const eskin::vboard::EngineOptions engine{sum.at("fpga_engine_shifter") == "barrel",
                                            sum.at("fpga_neurons") == "unit"};
  const eskin::vboard::FpgaBuild b =
      eskin::vboard::fpga_build_for(scene, "", long(clk), 3000000, engine);
  EXPECT_EQ(b.key, sum.at("fpga_build").get<std::string>()) << "the test derived another build";
  Bound r;
  r.clk_hz = clk;
  r.period = uint64_t(std::llround(clk / scene.skin.adc.rate_hz));
  const double total = double(eskin::hls::dtmf_frame_bound(b.plan).total());
  const double byte = 10.0 * double(std::llround(clk / b.baud()));
  r.clocks = double(r.period) + total / 2 + 2 * byte + 1;
  return r;
}

void expect_same_packets(const std::string& scene, const LevelRun& rtl) {
  const LevelRun pkt = simulate(scene, "packet");
  ASSERT_FALSE(rtl.link.empty());
  ASSERT_FALSE(pkt.link.empty());
  const Bound bound = arrival_bound(scene, rtl.summary);
  // At the end of the run the two may cut a packet differently: only the
  // packets arriving within the bound of the end may be missing from one.
  const double end_us = rtl.summary.at("sim_s").get<double>() * 1e6;
  const size_t n = std::min(rtl.link.size(), pkt.link.size());
  for (const auto* longer : {&rtl.link, &pkt.link})
    for (size_t i = n; i < longer->size(); ++i)
      EXPECT_GT((*longer)[i].arrival_us, end_us - 2 * bound.us()) << scene << " packet " << i;
  double worst = 0;
  size_t status = 0;
  for (size_t i = 0; i < n; ++i) {
    const LinkPacket& a = rtl.link[i];
    const LinkPacket& b = pkt.link[i];
    ASSERT_EQ(a.seq, b.seq) << scene << " packet " << i;
    ASSERT_EQ(a.type, b.type) << scene << " packet " << i;
    if (a.type == kStatusType) {  // its t and samples: the ADC counter when the engine read it
      ++status;
      EXPECT_LE(std::fabs(double(a.t) - double(b.t)), bound.clocks / double(bound.period) + 1)
          << scene << " status " << i;
      ASSERT_EQ(a.payload.size(), b.payload.size());
      EXPECT_EQ(a.payload.substr(0, kStatusSamplesHex), b.payload.substr(0, kStatusSamplesHex))
          << scene << " status " << i;
    } else {
      ASSERT_EQ(a.t, b.t) << scene << " packet " << i;
      ASSERT_EQ(a.payload, b.payload) << scene << " packet " << i << " type " << a.type;
    }
    const double d = std::fabs(a.arrival_us - b.arrival_us);
    worst = std::max(worst, d);
    EXPECT_LE(d, bound.us()) << scene << " packet " << i << " arrives at " << a.arrival_us
                             << " us on the RTL board, " << b.arrival_us << " us at packet level";
  }
  EXPECT_GT(status, 0u) << scene << ": no STATUS packet compared";
  std::printf("%s: %zu packets equal (%zu STATUS); arrival |packet - rtl| <= %.1f us, bound %.1f us\n",
              scene.c_str(), n, status, worst, bound.us());
  // The packet level is the faster one (its speed line names it).
  EXPECT_GT(pkt.summary.at("sim_s").get<double>() / pkt.summary.at("cpu_s").get<double>(),
            rtl.summary.at("sim_s").get<double>() / rtl.summary.at("cpu_s").get<double>());
}

}  // namespace

TEST(Fidelity, CycleAndPacketLevelsOnTheDefaultScene) {
  const LevelRun rtl = simulate("neuroskin2", "rtl");
  expect_same_record("neuroskin2", rtl, simulate("neuroskin2", "cycle"));
  expect_same_packets("neuroskin2", rtl);
}

TEST(Fidelity, CycleAndPacketLevelsOnPlanned3x3) {
  const LevelRun rtl = simulate("planned3x3", "rtl");
  expect_same_record("planned3x3", rtl, simulate("planned3x3", "cycle"));
  expect_same_packets("planned3x3", rtl);
}

// The cycle level has the board's pins: its line faults (the same seed)
// and board faults act there as on the Verilated board, and the host's
// record is the same, recoveries included.
TEST(Fidelity, CycleLevelUnderLineAndBoardFaults) {
  const std::vector<std::string> faults = {"--ber",   "2e-5",          "--fault", "reset@150",
                                           "--fault", "carrier-off=2@300:40", "--fault",
                                           "adc-stuck-high@450:10"};
  const LevelRun rtl = simulate("neuroskin2", "rtl", faults);
  const LevelRun cyc = simulate("neuroskin2", "cycle", faults);
  expect_same_record("neuroskin2 with faults", rtl, cyc);
  EXPECT_GT(rtl.summary.at("link_errors").get<double>(), 0) << "the line faults must show";
}

// staggered10x10's build has the neuron unit and the barrel shifter.
TEST(Fidelity, CycleAndPacketLevelsOnStaggered10x10) {
  const LevelRun rtl = simulate("staggered10x10", "rtl");
  expect_same_record("staggered10x10", rtl, simulate("staggered10x10", "cycle"));
  expect_same_packets("staggered10x10", rtl);
}

// The example scenes no iCEBreaker build keeps up with are refused alike at
// every level, before anything runs: the level does not change the build.
// (scenes/soak.yaml, the one example DTMF scene not compared above, is the
// default build's for 180 s: ten minutes of the RTL; its packets are the
// soak's, tests/vboard/line_faults_test.cpp.)
TEST(Fidelity, BothLevelsRefuseTheScenesTheBoardCannotBuild) {
  for (const char* scene : {"skin32x32", "skin64x64"}) {
    std::string said[3];
    int i = 0;
    for (const char* level : {"rtl", "cycle", "packet"}) {
      const fs::path out = fs::path(testing::TempDir()) / (std::string("fidelity_") + scene);
      std::string log;
      EXPECT_EQ(run_argv({ESKIN_BIN, "simulate",
                          std::string(ESKIN_SOURCE_DIR) + "/scenes/" + scene + ".yaml", "--fidelity",
                          level, "--out", out.string()},
                         &log),
                2)
          << log;
      said[i++] = log;
    }
    EXPECT_EQ(said[0], said[1]) << scene;
    EXPECT_EQ(said[0], said[2]) << scene;
    EXPECT_NE(said[0].find("error: skin: "), std::string::npos) << said[0];
  }
}

// What the faster levels do not model is refused, naming why, exit 2.
TEST(Fidelity, TheFasterLevelsRefuseWhatTheyDoNotModel) {
  const std::string dir = std::string(ESKIN_SOURCE_DIR) + "/scenes/";
  const fs::path out = fs::path(testing::TempDir()) / "fidelity_refused";
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{dir + "hall_000_skin.yaml"}, "Hall sensors"},
      {{dir + "mixed_neuroskin_split.yaml"}, "Hall sensors"},
      {{dir + "neuroskin2.yaml", "--trace", (out / "t.fst").string()}, "--trace"},
      {{dir + "neuroskin2.yaml", "--ber", "1e-4"}, "line faults"},
      {{dir + "neuroskin2.yaml", "--fault", "reset@10"}, "--fault"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> argv{ESKIN_BIN, "simulate", "--fidelity", "packet", "--out",
                                  out.string()};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    std::string log;
    EXPECT_EQ(run_argv(argv, &log), 2) << log;
    EXPECT_NE(log.find(c.says), std::string::npos) << log;
    EXPECT_NE(log.find("--fidelity"), std::string::npos) << log;
  }
  // The cycle level: the board's pins are there (faults run, above), but no
  // Hall model, no waveforms, and its own board executable.
  const std::vector<Case> cycle_cases = {
      {{dir + "hall_000_skin.yaml"}, "Hall sensors"},
      {{dir + "mixed_neuroskin_split.yaml"}, "Hall sensors"},
      {{dir + "neuroskin2.yaml", "--trace", (out / "t.fst").string()}, "--trace"},
      {{dir + "neuroskin2.yaml", "--board", ESKIN_BIN}, "--board"},
  };
  for (const Case& c : cycle_cases) {
    std::vector<std::string> argv{ESKIN_BIN, "simulate", "--fidelity", "cycle", "--out", out.string()};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    std::string log;
    EXPECT_EQ(run_argv(argv, &log), 2) << log;
    EXPECT_NE(log.find(c.says), std::string::npos) << log;
    EXPECT_NE(log.find("--fidelity"), std::string::npos) << log;
  }
  std::string log;
  EXPECT_EQ(run_argv({ESKIN_BIN, "simulate", dir + "neuroskin2.yaml", "--fidelity", "gate", "--out",
                      out.string()},
                     &log),
            2);
  EXPECT_NE(log.find("expected rtl, cycle or packet"), std::string::npos) << log;
}
