// The run-time configuration a Hall top's decoding needs from its host
// (docs/hall_fpga.md): the constants eskin's golden chain calibrates on the
// scene's own skin (host/hall/hall_chain.h), quantised to the HLS kernels'
// formats and sent as link commands (docs/protocol.md section 9):
//   DECOUPLE   3 HALL_SET_BASELINE (the geomagnetic field, recorded before
//              the film is placed, as seed 001 does) and HALL_SET_DECOUPLE;
//   FT         54 HALL_LOAD_C (C in mN per LSB, Q.16);
//   CURVE      NC x NB x 3 HALL_LOAD_CURVE (breakpoints, forces, slopes).
// `eskin simulate` sends them to the virtual board before the scene's first
// stimulus; the same frames configure a real board.
#pragma once

#include <cstdint>
#include <vector>

#include "host/hall/hall_chain.h"
#include "host/link/link_encoder.h"
#include "sim/hall_top_spec.h"

namespace eskin::hall {

struct HallFpgaSetup {
  std::vector<uint8_t> commands;  // framed, in the order to send
  size_t command_count = 0;
  DecoupleCalibration decouple;   // what the golden side decodes with
  WrenchCalibration wrench;
  std::vector<ForceCurve> curves;
};

// Throws ConfigError when the build's slots do not match the scene's
// sensors in the order the decoding expects.
HallFpgaSetup hall_fpga_setup(const sim::HallWorld& w, const sim::HallTopSpec& spec,
                              uint64_t seed, link::LinkEncoder& enc);

}  // namespace eskin::hall
