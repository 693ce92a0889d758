// eskin simulate on a Hall scene (docs/vboard.md, "Hall skins"): the
// scene's Hall build of rtl/hall_top.v on the virtual board with its
// MLX90393s on the I2C buses, read over the pty through host/stream; the
// decoding configured over the link from the golden chain's calibration;
// the golden chain run on the very readings the FPGA sent; both scored
// against the scene's truth; one HTML report plus the raw outputs.
#pragma once

#include <string>

#include "sim/scene.h"

namespace eskin::cli {

int run_simulate_hall(const sim::Scene& scene, const std::string& scene_file,
                      const std::string& out_dir, const std::string& trace);

}  // namespace eskin::cli
