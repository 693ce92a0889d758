// The skin's ADC side of a board: the scene's codes as the FPGA's 12-bit
// ADC gives them, with the board's ADC faults and the idle tail. Free of
// SystemC, so a board that is not the Verilated one (the packet level,
// host/simulate/packet_board.h) feeds the FPGA the very same samples.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sim/scene.h"
#include "sim/vboard/board_faults.h"

namespace eskin::vboard {

// A skin board's idle input after the scene (mid-scale codes), so that the
// last frames' packets get out before the run ends.
constexpr double kSkinTailS = 0.002;

struct SkinSamples {
  std::vector<uint16_t> codes;  // 12-bit codes, one per conversion (+ 64 spare past `samples`)
  uint64_t samples = 0;         // the run ends once the ADC has taken this many
  size_t scene_samples = 0;     // the scene's own (before the tail)
  double sample_hz = 0;
};

// The scene's codes << adc_shift, then `tail_s` of mid-scale; `faults`'
// ADC faults applied (carrier-off in the world, a stuck ADC on the codes).
SkinSamples skin_samples(const sim::Scene& scene, int adc_shift, double tail_s,
                         const std::vector<BoardFault>& faults = {});

}  // namespace eskin::vboard
