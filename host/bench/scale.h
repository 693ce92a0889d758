// `eskin bench scale`: the golden decoder's exact estimator (double) and the
// fast engine (integers, the FPGA's numbers) on skins from 3x3 to 256x256
// (512 carriers): samples/s on one core for the per-sample work (push a
// sample, every carrier's magnitude), the state memory, and the largest skin
// each keeps up with at 35 kSPS and at 1 MSPS. Carriers are planned on bin
// centres of the smallest power-of-two window that holds them.
#pragma once

#include <string>
#include <vector>

namespace eskin::bench {

struct ScaleRow {
  int rows = 0, cols = 0, carriers = 0, window = 0;
  double golden_sps = 0, engine_sps = 0;    // samples/s, one core (thread CPU time)
  double golden_mib = 0, engine_mib = 0;    // resident memory the decoder added
};

std::vector<ScaleRow> run_scale(int max_side, double min_seconds);
std::string format_scale(const std::vector<ScaleRow>& rows);

}  // namespace eskin::bench
