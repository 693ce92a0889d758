// eskin simulate on a Hall scene (docs/vboard.md, "Hall skins"): the
// scene's Hall build of rtl/hall_top.v on the virtual board with its
// MLX90393s on the I2C buses, read over the pty through host/stream; the
// decoding configured over the link from the golden chain's calibration;
// the golden chain run on the very readings the FPGA sent; both scored
// against the scene's truth; one HTML report plus the raw outputs.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "cli/board_link.h"
#include "cli/hall_fpga_setup.h"
#include "sim/scene.h"
#include "sim/vboard/hall_build.h"

namespace eskin::cli {

// The decoding's constants, calibrated by the golden chain on the scene's
// skin and quantised for the FPGA, with the commands that load them
// (host/cli/hall_fpga_setup.h).
HallFpgaSetup hall_simulation_setup(const sim::Scene& scene, const sim::HallTopSpec& spec);

// The Hall top's packets of a board run (`run.rx`, other types ignored):
// the golden chain on the FPGA's readings, both scored against the truth;
// report.html, hall_frames.csv, fpga_packets.ndjson and summary.json in
// `out_dir`; a summary on stdout. Returns summary.json's contents.
nlohmann::json report_hall(const sim::Scene& scene, const std::string& scene_file,
                           const vboard::HallBuild& build, const HallFpgaSetup& setup,
                           const BoardRun& run, const std::string& out_dir);

int run_simulate_hall(const sim::Scene& scene, const std::string& scene_file,
                      const std::string& out_dir, const std::string& trace);

}  // namespace eskin::cli
