// eskin golden SCENE.yaml [--out DIR]: world model + golden decoder on a
// scene; writes amplitudes, taxels and spikes (NDJSON and CSV) and prints a
// summary scored against the scene's ground truth.
#include <fmt/format.h>

#include <memory>

#include "cli/command.h"
#include "host/hall/hall_chain.h"
#include "host/simulate/golden_scene.h"
#include "sim/hall_world.h"
#include "sim/scene.h"

namespace eskin::cli {
namespace {

struct GoldenArgs {
  std::string scene;
  std::string out = "eskin-out";
  std::string variant;
  int hop = 0;
  bool no_ghost = false;
  int hall_osr = -1, hall_dig_filt = -1;
};

int run_golden(const GoldenArgs& a) {
  sim::Scene scene = sim::load_scene(a.scene);
  if (scene.has_hall) {
    fmt::print("scene {} ({}): magnetic skin\n", scene.name, a.scene);
    hall::apply_speed(scene.hall.config, a.hall_osr, a.hall_dig_filt);
    const sim::HallWorld hall(scene.hall);
    hall::run_hall_golden(hall, scene.duration_s, scene.seed, a.out);
    if (!scene.has_skin) return 0;
  }
  if (!a.variant.empty()) scene.decoder.variant = dft_variant_from_string(a.variant);
  if (a.hop > 0) scene.decoder.hop = a.hop;
  return simulate::run_golden_scene(scene, a.scene, a.out, !a.no_ghost);
}

std::function<int()> setup(CLI::App& app) {
  auto args = std::make_shared<GoldenArgs>();
  CLI::App* sub = app.add_subcommand(
      "golden", "Simulate a scene and decode it with the double-precision golden model");
  sub->add_option("scene", args->scene, "scene file (YAML, see docs/scenes.md)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", args->out, "output directory (created)")->capture_default_str();
  sub->add_option("--variant", args->variant,
                  "override decoder.variant: auto (default: the most accurate for the skin)|direct|"
                  "recursive|damped|exact (what the FPGA did before demixing)|ls");
  sub->add_option("--hop", args->hop, "override decoder.hop (frames every HOP samples)");
  sub->add_flag("--no-ghost", args->no_ghost, "report taxels without ghost correction");
  sub->add_option("--hall-osr", args->hall_osr, "Hall scenes: override the MLX90393 OSR (0..3)")
      ->check(CLI::Range(0, 3));
  sub->add_option("--hall-dig-filt", args->hall_dig_filt,
                  "Hall scenes: override the MLX90393 DIG_FILT (0..7)")
      ->check(CLI::Range(0, 7));
  return [args] { return run_golden(*args); };
}

ESKIN_COMMAND("golden", setup);

}  // namespace
}  // namespace eskin::cli
