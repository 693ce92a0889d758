// The report of `eskin simulate` on a Hall scene (docs/vboard.md, "Hall
// skins"): the Hall top's packets of a virtual board run, the golden chain
// run on the very readings the FPGA sent, both scored against the scene's
// truth; one HTML report plus the raw outputs.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "host/hall/hall_fpga_setup.h"
#include "host/stream/board_link.h"
#include "sim/scene.h"
#include "sim/vboard/hall_build.h"

namespace eskin::report {

// The Hall top's packets of a board run (`run.rx`, other types ignored):
// the golden chain on the FPGA's readings, both scored against the truth;
// report.html, hall_frames.csv, fpga_packets.ndjson and summary.json in
// `out_dir`; a summary on stdout. Returns summary.json's contents.
nlohmann::json report_hall(const sim::Scene& scene, const std::string& scene_file,
                           const vboard::HallBuild& build, const hall::HallFpgaSetup& setup,
                           const stream::BoardRun& run, const std::string& out_dir);

}  // namespace eskin::report
