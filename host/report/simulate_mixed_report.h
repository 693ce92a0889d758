// The report of `eskin simulate` on a scene with both a DTMF skin and Hall
// sensors (rtl/mixed_top.v on one board, both tops' packets on one link):
// the skin's packets scored as a DTMF scene's (OUT/skin), the Hall top's
// as a Hall scene's (OUT/hall); OUT/summary.json and OUT/report.html hold
// both and the shared link's figures.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "host/hall/hall_fpga_setup.h"
#include "host/report/simulate_dtmf_report.h"
#include "host/stream/board_link.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "sim/vboard/mixed_build.h"

namespace eskin::report {

// `dtmf`: the board's skin part; `setup`: the Hall decoding's configuration
// sent; `total`: the scene's samples. Returns OUT/summary.json's contents.
nlohmann::json report_mixed(const sim::Scene& scene, const std::string& scene_file,
                            const vboard::MixedBuild& build, const vboard::FpgaBuild& dtmf,
                            const GoldenRun& gold, const hall::HallFpgaSetup& setup,
                            const stream::BoardRun& run, size_t total, const std::string& out_dir);

}  // namespace eskin::report
