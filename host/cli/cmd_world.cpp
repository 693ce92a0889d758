// `eskin world SCENE.yaml [--wav OUT.wav] [--csv OUT.csv]`: runs the scene's
// DTMF world model and writes the ADC stream (and, in the CSV, the ground
// truth pressure of every touched taxel per sample).
#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/command.h"
#include "eskin/exit_codes.h"
#include "sim/scene.h"
#include "sim/wav_io.h"
#include "sim/world_model.h"

namespace {

struct WorldArgs {
  std::string scene, wav, csv;
};

void write_csv(const std::string& path, const eskin::sim::WorldModel& wm,
               const std::vector<int>& codes, int cols) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write CSV");
  out << "n,code";
  for (int t : wm.touched_taxels()) out << ",p_r" << t / cols << "_c" << t % cols << "_kpa";
  out << "\n";
  std::vector<double> kpa;
  char buf[32];
  for (size_t n = 0; n < codes.size(); ++n) {
    wm.pressure_at(n, kpa);
    out << n << ',' << codes[n];
    for (int t : wm.touched_taxels()) {
      std::snprintf(buf, sizeof buf, ",%.6g", kpa[size_t(t)]);
      out << buf;
    }
    out << '\n';
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

int run_world(const WorldArgs& a) {
  eskin::sim::Scene scene;
  try {
    scene = eskin::sim::load_scene(a.scene);
  } catch (const eskin::sim::SceneError& e) {
    std::cerr << "eskin world: " << e.what() << "\n";
    return eskin::exit_code(eskin::Exit::usage);
  }
  eskin::sim::WorldModel wm(scene);
  std::vector<int> codes = wm.all_codes();
  if (!a.wav.empty()) eskin::sim::write_wav(a.wav, codes, scene.skin.adc);
  if (!a.csv.empty()) write_csv(a.csv, wm, codes, scene.skin.cols);

  const auto& touched = wm.touched_taxels();
  std::cout << scene.name << ": " << codes.size() << " samples at " << scene.skin.adc.rate_hz
            << " Hz (" << scene.duration_s << " s), clipped " << wm.clipped() << ", touched taxels "
            << touched.size();
  if (touched.size() <= 16) {
    std::cout << ":";
    for (int t : touched) std::cout << " (" << t / scene.skin.cols << "," << t % scene.skin.cols << ")";
  }
  std::cout << "\n";
  return 0;
}

std::function<int()> setup_world(CLI::App& app) {
  auto args = std::make_shared<WorldArgs>();
  CLI::App* sub = app.add_subcommand(
      "world", "Run a scene's skin world model; write the ADC stream as WAV and/or CSV");
  sub->add_option("scene", args->scene, "Scene file (YAML, see docs/scenes.md)")->required();
  sub->add_option("--wav", args->wav,
                  "Write the ADC codes as mono 16-bit PCM WAV at the ADC rate");
  sub->add_option("--csv", args->csv,
                  "Write n, code and the ground-truth kPa of each touched taxel per sample");
  return [args] { return run_world(*args); };
}

}  // namespace

ESKIN_COMMAND("world", setup_world);
