// The golden model's side of `eskin simulate` on a DTMF skin: the scene
// decoded as written, and its spikes with neurons stepped like the FPGA's.
#pragma once

#include "host/report/simulate_dtmf_report.h"
#include "sim/scene.h"

namespace eskin::simulate {

// The golden model on the scene as written: frames at the scene's hop
// (every sample by default), neurons at its neuron.dt_ms. The FPGA steps
// its neurons once per frame (every `fpga_step` samples), a coarser Euler
// step that fires differently near threshold; a second run framed and
// stepped like it gives the spikes the FPGA's are compared with.
report::GoldenRun run_golden(const sim::Scene& scene, int fpga_step);

}  // namespace eskin::simulate
