// `eskin locate SCENE.yaml [--out DIR] [--max-contacts N] [--table]`: builds
// the seed-000 field table from a simulated calibration scan (the scene's
// locate: grid, Kriging-refined), then locates the contacts of every frame of
// the scene: writes contacts.csv (t, contact index, x, y, force; truth
// alongside) and prints the mean error of the steady frames. --table also
// writes the interpolated table (table.csv: x, y, then 3 values per sensor).
#include <memory>

#include "cli/command.h"
#include "host/hall/hall_locate.h"
#include "sim/scene.h"

namespace eskin::cli {
namespace {

struct LocateArgs {
  std::string scene;
  hall::HallLocateOptions opt;
};

int run_locate(const LocateArgs& a) {
  const sim::Scene scene = sim::load_scene(a.scene);
  if (!scene.has_hall) throw ConfigError("hall", a.scene + ": expected a scene with a hall: section");
  return hall::run_hall_locate(scene, a.opt);
}

std::function<int()> setup(CLI::App& app) {
  auto args = std::make_shared<LocateArgs>();
  CLI::App* sub = app.add_subcommand(
      "locate", "Build a Hall skin's field table from a calibration scan and locate contacts per frame");
  sub->add_option("scene", args->scene, "Hall scene file with a locate: grid (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", args->opt.out, "output directory (created)")->capture_default_str();
  sub->add_option("--max-contacts", args->opt.max_contacts, "contacts searched per frame")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  sub->add_flag("--table", args->opt.table, "also write the interpolated field table");
  return [args] { return run_locate(*args); };
}

ESKIN_COMMAND("locate", setup);

}  // namespace
}  // namespace eskin::cli
