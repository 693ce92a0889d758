// `eskin calibrate SCENE.yaml [--from PRESSES.csv] [--presses N]
//  [--write-presses OUT.csv] [--out CAL.yaml]`: fits the calibration every
// decoding block of a Hall scene needs: seed 002's 6x9 F/T matrix C by least
// squares (pseudo-inverse) from recorded presses (--from: CSV lines of
// b1x..b3z uT with the baseline removed, then fx fy fz N, tx ty tz N*mm) or
// from N simulated presses on the scene's skin; seed 001's Bz compensation
// and force polynomials; seed 003's force curves. Prints them and writes
// them as YAML (--out).
#include <memory>

#include "cli/command.h"
#include "host/hall/hall_calibrate.h"
#include "sim/scene.h"

namespace eskin::cli {
namespace {

struct CalibrateArgs {
  std::string scene;
  hall::HallCalibrateOptions opt;
};

int run_calibrate(const CalibrateArgs& a) {
  const sim::Scene scene = sim::load_scene(a.scene);
  if (!scene.has_hall) throw ConfigError("hall", a.scene + ": expected a scene with a hall: section");
  return hall::run_hall_calibrate(scene, a.scene, a.opt);
}

std::function<int()> setup(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* sub = app.add_subcommand(
      "calibrate", "Fit a Hall skin's calibration (F/T matrix, decoupling, force curves) from presses");
  sub->add_option("scene", args->scene, "Hall scene file (YAML)")->required()->check(CLI::ExistingFile);
  sub->add_option("--from", args->opt.from, "recorded presses (CSV: b1x..b3z, fx fy fz, tx ty tz)")
      ->check(CLI::ExistingFile);
  sub->add_option("--presses", args->opt.presses, "simulated presses for the F/T fit")
      ->capture_default_str()
      ->check(CLI::Range(9, 100000));
  sub->add_option("--write-presses", args->opt.write_presses, "write the simulated presses as a CSV recording");
  sub->add_option("--out", args->opt.out, "write the calibration as YAML");
  return [args] { return run_calibrate(*args); };
}

ESKIN_COMMAND("calibrate", setup);

}  // namespace
}  // namespace eskin::cli
