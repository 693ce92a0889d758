// One 3-axis Hall sample as the FPGA's MLX90393 sequencer emits it and the
// decoders (golden, HLS, RTL) consume it: sensor id, timestamp, the signed
// field values in LSB of the sensor's RES setting, and flags.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "eskin/hall_config.h"

namespace eskin {

// The flags of the FPGA sequencer's tokens (rtl/mlx90393_sequencer.v).
enum HallSampleFlag : uint8_t {
  kHallSatX = 0x01, kHallSatY = 0x02, kHallSatZ = 0x04,  // code at its format's rail
  kHallMissing = 0x08,    // the sensor NACKed
  kHallError = 0x10,      // status ERROR: sample dropped
  kHallReply = 0x20,      // unexpected reply: not trusted
  kHallBus = 0x40,        // bus timeout / SDA stuck
  kHallRecovered = 0x80,  // SDA was recovered before this transaction
  kHallNoData = kHallMissing | kHallError | kHallReply | kHallBus,
};

struct HallSample {
  uint8_t sensor = 0;
  uint32_t t_us = 0;
  std::array<int16_t, 3> lsb{0, 0, 0};
  uint8_t flags = 0;
};

// Field in uT of a sample under the sensors' setting.
inline Vec3 sample_ut(const mlx90393::Config& c, const HallSample& s) {
  return {s.lsb[0] * mlx90393::sensitivity_uT(c, 0), s.lsb[1] * mlx90393::sensitivity_uT(c, 1),
          s.lsb[2] * mlx90393::sensitivity_uT(c, 2)};
}

// One complete frame: the latest sample of every sensor, in sensor order.
using HallFrame = std::vector<HallSample>;

}  // namespace eskin
