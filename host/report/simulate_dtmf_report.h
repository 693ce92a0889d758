// The report of `eskin simulate` on a DTMF skin (docs/vboard.md): the
// skin's packets of a virtual board run scored against the scene's truth
// and the golden model; one HTML report plus the raw outputs.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/fpga/scale_table.h"
#include "host/golden/decode_score.h"
#include "host/golden/golden_decoder.h"
#include "host/stream/board_link.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"

namespace eskin::report {

// The golden model's run the FPGA's packets are compared with
// (host/simulate/golden_run.h makes it).
struct GoldenRun {
  std::vector<golden::Frame> frames;  // by sample index (empty before the window fills)
  // Spikes of the receptors and the second layer, neurons stepped like the
  // FPGA's (once per frame); and the receptors' count at the scene's own
  // neuron step (neuron.dt_ms, one sample by default).
  std::vector<std::vector<double>> spikes_ms, spikes2_ms;
  size_t scene_step_spikes = 0, scene_step_spikes2 = 0;
  golden::DecodeScore score;
};

// The build's frame engine, as `eskin bitstream --engine-shifter` and
// `--neurons` name it.
fpga::EngineVariant engine_of(const vboard::FpgaBuild& b);

// The DTMF skin's packets of a board run (`run.rx`, other types ignored),
// scored against the truth and the golden model: report.html, CSVs,
// fpga_packets.ndjson and summary.json in `out_dir`; a summary on stdout.
// Returns summary.json's contents.
nlohmann::json report_dtmf(const sim::Scene& scene, const std::string& scene_file,
                           const vboard::FpgaBuild& build, const GoldenRun& gold,
                           const stream::BoardRun& run, size_t total, const std::string& out_dir);

}  // namespace eskin::report
