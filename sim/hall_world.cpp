#include "sim/hall_world.h"

namespace eskin::sim {

HallWorld::HallWorld(const HallScene& scene) : scene_(scene), field_(scene_.config) {}

const std::vector<CellPose>& HallWorld::poses_at(double t_s) const {
  if (t_s != cached_t_ || cached_.empty()) {
    std::vector<ContactLoad> contacts;
    std::vector<PlateWrench> plate;
    scene_.loads_at(t_s, contacts, plate);
    cached_ = cell_poses(scene_.config, contacts, plate);
    cached_t_ = t_s;
  }
  return cached_;
}

std::array<double, 3> HallWorld::field_uT(int sensor, double t_s) const {
  return field_.at_sensor(size_t(sensor), poses_at(t_s));
}

std::vector<Vec3> HallWorld::fields_under(const std::vector<ContactLoad>& contacts,
                                          const std::vector<PlateWrench>& plate) const {
  return field_.at_sensors(cell_poses(scene_.config, contacts, plate));
}

HallTruth HallWorld::truth(double t_s) const {
  HallTruth t;
  t.t_s = t_s;
  std::vector<PlateWrench> plate;
  scene_.loads_at(t_s, t.contacts, plate);
  t.cells = cell_poses(scene_.config, t.contacts, plate);
  const double z = scene_.surface_z_mm();
  for (const auto& c : t.contacts) {
    const Vec3 r{c.point_mm[0], c.point_mm[1], c.point_mm[2] - z};
    const Vec3& f = c.force_n;
    for (size_t k = 0; k < 3; ++k) t.force_n[k] += f[k];
    t.torque_nmm[0] += r[1] * f[2] - r[2] * f[1];
    t.torque_nmm[1] += r[2] * f[0] - r[0] * f[2];
    t.torque_nmm[2] += r[0] * f[1] - r[1] * f[0];
  }
  for (const auto& w : plate)
    for (size_t k = 0; k < 3; ++k) t.force_n[k] += w.force_n[k], t.torque_nmm[k] += w.torque_nmm[k];
  return t;
}

}  // namespace eskin::sim
