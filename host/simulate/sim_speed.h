// eskin bench sim-speed: how fast each fidelity level of the virtual board
// runs each scene, side by side in one run (docs/bench.md). Each row is one
// `eskin simulate SCENE --fidelity LEVEL` as a child process; its figures
// are the ones its summary.json reports: simulated seconds, and the CPU
// seconds of the board's own work (the board process at rtl and cycle, the
// packet model's thread at packet; the golden model and the report are
// not counted), so "x real time" is simulated s per CPU s.
#pragma once

#include <string>
#include <vector>

#include "host/simulate/simulate.h"

namespace eskin::simulate {

// One column of the comparison: a level, and more `eskin simulate`
// options (a Verilator variant's --board), under a label.
struct SimSpeedConfig {
  std::string label;
  Fidelity level = Fidelity::rtl;
  std::vector<std::string> extra;
  bool default_build_only = false;  // a board of the default build: other scenes get no row
};

struct SimSpeedRow {
  std::string scene, level;
  bool ran = false;
  std::string why;  // when !ran: what the level said (it does not model the scene)
  double sim_s = 0, cpu_s = 0, wall_s = 0, cycles = 0;
  double x_real_time() const { return cpu_s > 0 ? sim_s / cpu_s : 0; }
};

// Runs every scene in every configuration with `eskin_bin`, outputs under
// `work_dir`; a row's `level` is its configuration's label. A level that refuses a scene (exit 2: it does not model it)
// gives a row saying why; any other failure throws std::runtime_error
// naming the command and its log.
std::vector<SimSpeedRow> measure_sim_speed(const std::string& eskin_bin,
                                           const std::vector<std::string>& scenes,
                                           const std::vector<SimSpeedConfig>& configs,
                                           const std::string& work_dir);

// The table, one row per scene and configuration, with each one's speed
// against the first's on the same scene.
std::string format_sim_speed(const std::vector<SimSpeedRow>& rows);

// The rows as CSV (name,value,unit,source; names SCENE/LABEL/sim_s,
// cpu_s, x_real_time): `command` is the source.
std::string sim_speed_csv(const std::vector<SimSpeedRow>& rows, const std::string& command);

}  // namespace eskin::simulate
