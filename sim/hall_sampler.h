// Samples a Hall world the way the MLX90393s deliver it to the FPGA: every
// sensor converts X, Y, Z back to back in burst mode at the device's maximum
// output rate for the scene's OSR/DIG_FILT (mlx90393::conversion_us), adds
// its white noise (scene noise_rms_ut) and quantises with the device's own
// code law (mlx90393::encode_uT: sensitivity per GAIN_SEL/RES, clamping).
// Used by the golden chain, calibration and localisation; the cycle-level
// path through the I2C bus and sequencer is hall-bus's device model.
#pragma once

#include <random>
#include <vector>

#include "eskin/hall_sample.h"
#include "sim/hall_world.h"

namespace eskin::sim {

class HallSampler {
 public:
  HallSampler(const HallConfig& cfg, uint64_t seed);
  // The frame period (s): one XYZ conversion.
  double period_s() const;
  // One frame: every sensor's sample of `field` (uT per sensor) at time t.
  HallFrame sample(const std::vector<Vec3>& field, double t_s);
  // Every sensor at time t of the world.
  HallFrame sample(const HallWorld& world, double t_s);

 private:
  const HallConfig& cfg_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> noise_{0.0, 1.0};
};

}  // namespace eskin::sim
