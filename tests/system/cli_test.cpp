// The eskin CLI as a user runs it: real processes, real files, exit codes
// and messages. Bad input must fail with a message naming the file and what
// was expected; good input must produce the documented outputs.
#include <gtest/gtest.h>
#include <sndfile.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include <map>

#include "host/engine/dtmf_engine.h"
#include "host/engine/engine_setup.h"
#include "sim/scene.h"
#include "sim/wav_io.h"
#include "sim/world_model.h"

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

using Result = CliResult;
Result sh(const std::string& args) { return run_eskin(args); }

fs::path tmpdir() {
  fs::path d = fs::temp_directory_path() /
               ("eskin_cli_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::create_directories(d);
  return d;
}

const std::string kScene = ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml";

size_t count_lines(const fs::path& p) {
  std::ifstream f(p);
  return size_t(std::count(std::istreambuf_iterator<char>(f), {}, '\n'));
}

TEST(Cli, HelpListsEverySubcommand) {
  const Result r = sh("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* c : {"golden", "decode", "neuron", "world"})
    EXPECT_NE(r.out.find(c), std::string::npos) << c << " missing from\n" << r.out;
}

TEST(Cli, GoldenOnDefaultSceneWritesEveryOutput) {
  const fs::path d = tmpdir();
  const Result r = sh("golden " + kScene + " --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* f : {"amplitudes.ndjson", "amplitudes.csv", "taxels.ndjson", "taxels.csv",
                        "spikes.ndjson", "spikes.csv"})
    EXPECT_GT(count_lines(d / f), 1u) << f;
  EXPECT_NE(r.out.find("ghosts"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("spikes:"), std::string::npos) << r.out;
  // One amplitude frame per sample once the 32-sample window is full.
  const eskin::sim::Scene s = eskin::sim::load_scene(kScene);
  const size_t samples = eskin::sim::WorldModel(s).total_samples();
  EXPECT_EQ(count_lines(d / "amplitudes.ndjson"),
            (samples - size_t(s.decoder.window)) / size_t(s.decoder.hop) + 1);
}

TEST(Cli, GoldenRejectsABadSceneBeforeRunning) {
  const fs::path d = tmpdir();
  std::ifstream in(kScene);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string y = ss.str();
  const size_t at = y.find("rows:");
  ASSERT_NE(at, std::string::npos);
  y.replace(at, 5, "rowz:");
  std::ofstream(d / "bad.yaml") << y;
  const Result r = sh("golden " + (d / "bad.yaml").string() + " --out " + (d / "o").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("bad.yaml:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rowz"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "o")) << "outputs were written for a rejected scene";
}

// Writes the default scene's stream as WAV through the world model.
fs::path scene_wav(const fs::path& d) {
  const eskin::sim::Scene s = eskin::sim::load_scene(kScene);
  eskin::sim::WorldModel w(s);
  const fs::path p = d / "scene.wav";
  eskin::sim::write_wav(p.string(), w.all_codes(), s.skin.adc);
  return p;
}

TEST(Cli, DecodeOfTheWorldModelsWavEqualsGoldenAmplitudes) {
  // The WAV carries the ADC codes exactly (10-bit codes << 6 in 16-bit PCM),
  // so decoding it must reproduce the golden run's amplitudes line for line.
  const fs::path d = tmpdir();
  const fs::path wav = scene_wav(d);
  ASSERT_EQ(sh("golden " + kScene + " --out " + d.string()).status, 0);
  const Result r = sh("decode --skin " + kScene + " " + wav.string());
  ASSERT_EQ(r.status, 0) << r.out.substr(0, 500);
  std::ifstream g(d / "amplitudes.ndjson");
  std::istringstream dec(r.out);
  std::string gl, dl;
  size_t lines = 0;
  while (std::getline(g, gl)) {
    ASSERT_TRUE(std::getline(dec, dl)) << "decode stopped after " << lines << " lines";
    EXPECT_EQ(dl, gl);
    ++lines;
  }
  EXPECT_GT(lines, 1000u);
}

void write_raw(const fs::path& p, int channels, int rate, int frames, int format) {
  SF_INFO info{};
  info.channels = channels;
  info.samplerate = rate;
  info.format = format;
  SNDFILE* f = sf_open(p.c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr);
  std::vector<short> s(size_t(frames * channels), 100);
  sf_writef_short(f, s.data(), frames);
  sf_close(f);
}

TEST(Cli, DecodeRejectsBadWavsWithAClearMessage) {
  const fs::path d = tmpdir();
  struct Case {
    std::string file, expect;
  };
  write_raw(d / "stereo.wav", 2, 35000, 1000, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  write_raw(d / "rate.wav", 1, 44100, 1000, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  write_raw(d / "float.wav", 1, 35000, 1000, SF_FORMAT_WAV | SF_FORMAT_FLOAT);
  std::ofstream(d / "text.wav") << "this is not a wav file\n";
  const fs::path good = scene_wav(d);
  const auto size = fs::file_size(good);
  fs::copy_file(good, d / "cut.wav");
  fs::resize_file(d / "cut.wav", size / 2);
  const Case cases[] = {{"stereo.wav", "mono"},
                        {"rate.wav", "sample rate 44100"},
                        {"float.wav", "16-bit PCM"},
                        {"text.wav", "text.wav"},
                        {"cut.wav", "truncated"}};
  for (const Case& c : cases) {
    const Result r = sh("decode --skin " + kScene + " " + (d / c.file).string());
    EXPECT_NE(r.status, 0) << c.file;
    EXPECT_NE(r.out.find(c.file), std::string::npos) << c.file << ": " << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.file << ": " << r.out;
  }
}

TEST(Cli, NeuronPrintsSpikesAndRejectsBadPresets) {
  const Result ok = sh("neuron --preset RS --input step:10@10 --duration 200");
  ASSERT_EQ(ok.status, 0) << ok.out;
  EXPECT_NE(ok.out.find("\"t_ms\""), std::string::npos) << ok.out;
  const Result bad = sh("neuron --preset XX --input step:10 --duration 100");
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.out.find("XX"), std::string::npos) << bad.out;
}


// `eskin decode --engine fpga`: the NDJSON amplitudes, pressures and
// spikes are the engine's packets (host/engine, itself equal to
// hls/dtmf_chain.h) for the WAV's codes, line for line, with the top's
// ghost filter on (taxels no longer need --no-ghost). Bound: amplitudes
// equal to the printed 6 significant digits (2 mag / N is printed with
// %.6g); spike lists equal.
TEST(Cli, DecodeFpgaEngineIsTheEnginesPackets) {
  const fs::path d = tmpdir();
  const auto scene = eskin::sim::load_scene(kScene);
  eskin::sim::WorldModel world(scene);
  const std::vector<int> codes = world.all_codes();
  eskin::sim::write_wav((d / "s.wav").string(), codes, scene.skin.adc);
  const Result r = sh("decode --skin " + kScene + " " + (d / "s.wav").string() +
                      " --engine fpga --hop 35 --spikes --threads 2");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto plan = eskin::engine::top_plan(scene.skin, scene.decoder, scene.neuron, true);
  ASSERT_EQ(plan.step, 35);
  ASSERT_TRUE(plan.spec.ghost);
  const auto c12 = eskin::engine::codes12(codes, scene.skin.adc.bits);
  const auto ps = eskin::engine::DtmfEngine(eskin::engine::engine_config(plan)).run(c12.data(), c12.size());
  std::map<uint32_t, std::string> amp, spk;
  for (const auto& p : ps.packets) {
    const uint8_t* b = ps.payload(p);
    std::string& s = p.type == 1 ? amp[p.t] : spk[p.t];
    for (uint32_t i = 0; p.type == 1 && i < p.len; i += 2)
      s += fmt::format("{}{:.6g}", i ? "," : "", (b[i] | b[i + 1] << 8) * 2.0 / 32);
    for (uint32_t i = 0; p.type == 4 && i < p.len; i += 5)
      if (b[i + 2] == 0) s += fmt::format("{}{}", s.empty() ? "" : ",", b[i + 3] | b[i + 4] << 8);
  }
  std::istringstream lines(r.out);
  std::string line;
  size_t n = 0, with_spikes = 0;
  for (; std::getline(lines, line); ++n) {
    const uint32_t t = uint32_t(std::stoul(line.substr(line.find(':') + 1)));
    EXPECT_NE(line.find("\"amp_lsb\":[" + amp.at(t) + "]"), std::string::npos) << line;
    EXPECT_NE(line.find("\"spikes\":[" + spk[t] + "]"), std::string::npos) << line;
    EXPECT_NE(line.find("\"pressure_kpa\":["), std::string::npos) << line;
    with_spikes += !spk[t].empty();
  }
  EXPECT_EQ(n, amp.size());
  EXPECT_EQ(n, (codes.size() - 32) / 35 + 1);  // a frame once the window is full, then every 35
  EXPECT_GE(with_spikes, 5u);
  const Result bad = sh("decode --skin " + kScene + " " + (d / "s.wav").string() +
                        " --engine fpga --variant recursive");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("--variant"), std::string::npos) << bad.out;
  const Result hop = sh("decode --skin " + kScene + " " + (d / "s.wav").string() +
                        " --engine fpga --taxels --hop 36");
  EXPECT_EQ(hop.status, 2);
  EXPECT_NE(hop.out.find("--hop"), std::string::npos) << hop.out;
}

// ---- Hall scenes (docs/hall.md)

TEST(Cli, GoldenRunsAHallSceneAndScoresIt) {
  const fs::path d = tmpdir();
  const Result r = sh("golden " ESKIN_SOURCE_DIR "/scenes/hall_003_metamaterial.yaml --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("9 sensors on 1 bus(es)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("range 3 (4.8..16.2 N)"), std::string::npos) << r.out;
  // One NDJSON line per frame after the baseline: 4 s at 487 Hz is 1948 frames.
  EXPECT_GT(count_lines(d / "hall.ndjson"), 1800u);
  // An illegal speed setting is refused, naming it.
  const Result bad = sh("golden " ESKIN_SOURCE_DIR "/scenes/hall_003_metamaterial.yaml --hall-osr 0 --hall-dig-filt 1 --out " + d.string());
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.out.find("dig_filt"), std::string::npos) << bad.out;
}

TEST(Cli, CalibrateFitsTheSameMatrixFromRecordedPresses) {
  const fs::path d = tmpdir();
  const std::string scene = ESKIN_SOURCE_DIR "/scenes/hall_002_magtac.yaml";
  const Result sim = sh("calibrate " + scene + " --presses 40 --write-presses " + (d / "p.csv").string() +
                        " --out " + (d / "sim.yaml").string());
  ASSERT_EQ(sim.status, 0) << sim.out;
  const Result rec = sh("calibrate " + scene + " --from " + (d / "p.csv").string() + " --out " + (d / "rec.yaml").string());
  ASSERT_EQ(rec.status, 0) << rec.out;
  EXPECT_NE(rec.out.find("from 40 recorded presses"), std::string::npos) << rec.out;
  // The recording carries fields and wrenches to 1e-6 (uT, N, N*mm), about
  // 1e-9 of their size; the fit (condition number well under 1e4 here)
  // moves by far less than 1e-4 of the largest entry: bound 1e-4.
  const YAML::Node a = YAML::LoadFile((d / "sim.yaml").string())["wrench_matrix"];
  const YAML::Node b = YAML::LoadFile((d / "rec.yaml").string())["wrench_matrix"];
  ASSERT_EQ(a.size(), 54u);
  ASSERT_EQ(b.size(), 54u);
  double big = 0;
  for (size_t i = 0; i < 54; ++i) big = std::max(big, std::fabs(a[i].as<double>()));
  for (size_t i = 0; i < 54; ++i) EXPECT_NEAR(a[i].as<double>(), b[i].as<double>(), 1e-4 * big) << i;
  EXPECT_EQ(count_lines(d / "p.csv"), 41u);
  // A malformed recording names its file and line.
  std::ofstream(d / "bad.csv") << "b1x,b1y\n1,2,3\n";
  const Result bad = sh("calibrate " + scene + " --from " + (d / "bad.csv").string());
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.out.find("bad.csv:2: expected 15 numbers"), std::string::npos) << bad.out;
}

TEST(Cli, LocateWritesContactsOfTheSeed000Scene) {
  const fs::path d = tmpdir();
  const Result r = sh("locate " ESKIN_SOURCE_DIR "/scenes/hall_000_skin.yaml --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("table: 500x500 entries at 0.44 mm"), std::string::npos) << r.out;
  EXPECT_GT(count_lines(d / "contacts.csv"), 2000u);
  // Seed 000 has nothing for calibrate (its table is built by locate).
  const Result none = sh("calibrate " ESKIN_SOURCE_DIR "/scenes/hall_000_skin.yaml");
  EXPECT_NE(none.status, 0);
  EXPECT_NE(none.out.find("use eskin locate"), std::string::npos) << none.out;
}

}  // namespace

