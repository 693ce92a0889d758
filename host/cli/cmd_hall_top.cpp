// `eskin hall-top SCENE.yaml [--clk-mhz F]`: the rtl/hall_top.v build a Hall
// scene needs (sim/hall_top_spec.h: buses, sensors per bus, addresses and
// TCA9548A channels, the MLX90393 registers, the conversion waits at that
// clock, and the decoding the scene's `decode:` list asks for), printed as
// NAME=VALUE lines, one per Verilog parameter, for Verilator -G or Yosys
// chparam. A scene whose sensors hall_top cannot carry is refused with the
// field named.
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "cli/command.h"
#include "sim/hall_top_spec.h"
#include "sim/scene.h"

namespace eskin::cli {
namespace {

struct HallTopArgs {
  std::string scene;
  int clk_mhz = 12;
};

int run_hall_top(const HallTopArgs& a) {
  const sim::Scene scene = sim::load_scene(a.scene);  // names the bad field
  if (!scene.has_hall) throw ConfigError("hall", a.scene + ": expected a scene with a hall: section");
  const sim::HallTopSpec s = sim::hall_top_spec(scene.hall.config, a.clk_mhz * 1e6);
  std::vector<std::string> params{"-GCLK_HZ=" + std::to_string(a.clk_mhz * 1000000L)};
  for (const auto& p : s.verilog_params()) params.push_back(p);
  for (const auto& p : s.decode_params()) params.push_back(p);
  for (const auto& p : params) fmt::print("{}\n", p.substr(2));  // without "-G"
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  auto args = std::make_shared<HallTopArgs>();
  CLI::App* sub = app.add_subcommand(
      "hall-top", "Print the rtl/hall_top.v parameters (NAME=VALUE) a Hall scene needs");
  sub->add_option("scene", args->scene, "Hall scene (.yaml)")->required()->check(CLI::ExistingFile);
  sub->add_option("--clk-mhz", args->clk_mhz, "FPGA clock in whole MHz (hall_top needs a whole MHz)")
      ->capture_default_str()
      ->check(CLI::Range(1, 200));
  return [args] { return run_hall_top(*args); };
}

ESKIN_COMMAND("hall-top", setup);

}  // namespace
}  // namespace eskin::cli
