// The world of a magnetic skin scene: the field at each Hall sensor over time
// (physics of sim/hall_physics.h under the scene's stimuli) and the ground
// truth (contacts, forces, torque, cell poses) to score decoders against.
// Implements HallFieldSource for the MLX90393 device model.
#pragma once

#include <array>
#include <vector>

#include "sim/hall_field_source.h"
#include "sim/hall_physics.h"
#include "sim/hall_scene.h"

namespace eskin::sim {

struct HallTruth {
  double t_s = 0;
  std::vector<ContactLoad> contacts;   // point loads acting (force on the skin, z up)
  Vec3 force_n{0, 0, 0};               // sum of all contact and plate forces
  Vec3 torque_nmm{0, 0, 0};            // about the plate/skin origin (0, 0, surface z)
  std::vector<CellPose> cells;         // per cell, force_n = what it carries
};

class HallWorld : public HallFieldSource {
 public:
  explicit HallWorld(const HallScene& scene);
  HallWorld(const HallWorld&) = delete;
  HallWorld& operator=(const HallWorld&) = delete;

  std::array<double, 3> field_uT(int sensor, double t_s) const override;
  // Every sensor's field under explicit loads (calibration presses and scans).
  std::vector<Vec3> fields_under(const std::vector<ContactLoad>& contacts,
                                 const std::vector<PlateWrench>& plate = {}) const;
  HallTruth truth(double t_s) const;
  const HallScene& scene() const { return scene_; }
  const HallConfig& config() const { return scene_.config; }

 private:
  const std::vector<CellPose>& poses_at(double t_s) const;

  HallScene scene_;
  HallField field_;
  mutable double cached_t_ = -1;
  mutable std::vector<CellPose> cached_;
};

}  // namespace eskin::sim
