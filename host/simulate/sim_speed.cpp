#include "host/simulate/sim_speed.h"

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "eskin/process.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"

namespace eskin::simulate {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The run's own figures: a mixed scene's are its skin part's (both parts
// ran on the one board).
const nlohmann::json& figures_of(const nlohmann::json& sum) {
  return sum.contains("sim_s") ? sum : sum.at("skin");
}

}  // namespace

std::vector<SimSpeedRow> measure_sim_speed(const std::string& eskin_bin,
                                           const std::vector<std::string>& scenes,
                                           const std::vector<SimSpeedConfig>& configs,
                                           const std::string& work_dir) {
  std::vector<SimSpeedRow> rows;
  for (const std::string& scene : scenes) {
    const std::string stem = std::filesystem::path(scene).stem().string();
    const sim::Scene sc = sim::load_scene(scene);
    const bool default_build = sc.has_skin && !sc.has_hall && vboard::fpga_build_for(sc).key == "default";
    for (const SimSpeedConfig& c : configs) {
      if (c.default_build_only && !default_build) continue;
      SimSpeedRow r;
      r.scene = stem;
      r.level = c.label;
      std::string dir = stem + "-" + c.label;
      std::replace(dir.begin(), dir.end(), '/', '-');
      const std::filesystem::path out = std::filesystem::path(work_dir) / dir;
      std::filesystem::create_directories(out);
      const std::string log = (out / "simulate.log").string();
      std::vector<std::string> argv{eskin_bin, "simulate",          scene,
                                    "--fidelity", fidelity_name(c.level), "--out", out.string()};
      argv.insert(argv.end(), c.extra.begin(), c.extra.end());
      const int st = run_logged(argv, log);
      const int code = st >= 0 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
      if (code == 2) {  // refused: say what it said
        const std::string text = slurp(log);
        const size_t at = text.find("error: ");
        r.why = at == std::string::npos ? text : text.substr(at + 7);
        while (!r.why.empty() && (r.why.back() == '\n' || r.why.back() == '\r')) r.why.pop_back();
        rows.push_back(r);
        continue;
      }
      if (code != 0)
        throw std::runtime_error(fmt::format("sim-speed: {} failed (exit {}); its log: {}",
                                             printable_command(argv), code, log));
      const nlohmann::json sum = nlohmann::json::parse(slurp(out / "summary.json"));
      const nlohmann::json& fig = figures_of(sum);
      r.ran = true;
      r.sim_s = fig.at("sim_s");
      r.cpu_s = fig.at("cpu_s");
      r.wall_s = fig.at("wall_s");
      r.cycles = fig.at("cycles");
      rows.push_back(r);
    }
  }
  return rows;
}

std::string format_sim_speed(const std::vector<SimSpeedRow>& rows) {
  std::string s = fmt::format("{:<22} {:<20} {:>9} {:>9} {:>12} {:>12} {:>9}\n", "scene", "level",
                              "sim s", "CPU s", "x real time", "cycles/CPU s", "vs first");
  double first = 0;
  std::string scene;
  for (const SimSpeedRow& r : rows) {
    if (r.scene != scene) scene = r.scene, first = r.ran ? r.x_real_time() : 0;
    if (!r.ran) {
      s += fmt::format("{:<22} {:<20} not modelled: {}\n", r.scene, r.level, r.why);
      continue;
    }
    s += fmt::format("{:<22} {:<20} {:>9.3f} {:>9.3f} {:>12.3f} {:>12.3g} {:>9}\n", r.scene,
                     r.level, r.sim_s, r.cpu_s, r.x_real_time(), r.cycles / r.cpu_s,
                     first > 0 ? fmt::format("{:.1f}x", r.x_real_time() / first) : "-");
  }
  return s;
}

std::string sim_speed_csv(const std::vector<SimSpeedRow>& rows, const std::string& command) {
  std::string s =
      "# The virtual board's fidelity levels (docs/bench.md, \"Simulation speed\"), written by\n"
      "# `eskin bench sim-speed --csv` (host/simulate/sim_speed.h). CPU s: the board's own\n"
      "# work; the rows ran side by side in one run on one machine.\n"
      "name,value,unit,source\n";
  for (const SimSpeedRow& r : rows) {
    if (!r.ran) continue;
    const std::string k = r.scene + "/" + r.level + "/";
    s += fmt::format("{}sim_s,{:.4f},s,\"{}\"\n", k, r.sim_s, command);
    s += fmt::format("{}cpu_s,{:.3f},s,\"{}\"\n", k, r.cpu_s, command);
    s += fmt::format("{}x_real_time,{:.3g},simulated s per CPU s,\"{}\"\n", k, r.x_real_time(),
                     command);
  }
  return s;
}

}  // namespace eskin::simulate
