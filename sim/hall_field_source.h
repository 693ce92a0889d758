// Where a Hall sensor model gets its field from: the magnetic physics
// (hall-decode's world model) implements it; the MLX90393 device model
// (sim/mlx90393_model.h) reads it at each conversion and adds its own noise,
// offset and quantisation. Tests implement it with fixed or scripted fields.
#pragma once

#include <array>

namespace eskin::sim {

struct HallFieldSource {
  virtual ~HallFieldSource() = default;
  // Flux density (Bx, By, Bz) in µT at sensor `sensor` (the scene's index)
  // at simulated time t_s (seconds), in the sensor's own axes.
  virtual std::array<double, 3> field_uT(int sensor, double t_s) const = 0;
};

}  // namespace eskin::sim
