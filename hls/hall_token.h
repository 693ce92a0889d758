// Tokens of the Hall decoding chain on the FPGA.
//
// HallSampleToken: what rtl/mlx90393_sequencer.v emits per sensor reading:
// sensor id, timestamp, the three axis codes exactly as the MLX90393 sends
// them (two's complement at RES 0/1; offset binary 0x8000 at RES 2 or with
// TCMP; 0x4000 at RES 3) and flags: bits 0..2 X/Y/Z at a rail (saturated),
// 3 MISSING (NACK), 4 ERROR (status), 5 REPLY (not trusted), 6 BUS, 7 SDA
// recovered. A token with any of bits 3..6 carries no data.
//
// HallDeltaToken: hall_baseline's output: the same sensor's field change in
// signed LSB (int16, saturated), flags passed on.
#pragma once

#include <cstdint>

namespace eskin::hls {

constexpr uint8_t kHallFlagSat = 0x07;
constexpr uint8_t kHallFlagNoData = 0x78;

struct HallSampleToken {
  uint8_t id = 0;
  uint32_t t = 0;
  uint16_t x = 0, y = 0, z = 0;
  uint8_t flags = 0;
};

struct HallDeltaToken {
  uint8_t id = 0;
  uint32_t t = 0;
  int16_t d[3] = {0, 0, 0};
  uint8_t flags = 0;
};

// Saturate a 32-bit value to int16.
inline int16_t sat16(int32_t v) { return int16_t(v > 32767 ? 32767 : v < -32768 ? -32768 : v); }

}  // namespace eskin::hls
