// Magnetic and mechanical physics of a Hall skin (seeds 000..003).
//
// Field model: every magnet is replaced by its equivalent (Amperian) surface
// currents, discretised into closed polygons of straight segments, and B is
// the exact Biot-Savart sum over the segments. Why not a point dipole: the
// seed-000 films are 37.5 mm wide at 30 mm from the sensors and the seed-002/
// 003 magnets sit 2..12 mm from theirs, i.e. at distances comparable to their
// size, where a dipole is off by tens of percent; and the seed-001 film is
// magnetised in plane from its sides to its centre, so its net dipole moment is
// zero and a dipole model gives no field at all. The current model is exact
// for uniform magnetisation up to the discretisation (tested against the
// closed-form on-axis field of a cylinder and the far dipole field):
//  - Box/Cylinder magnetised along body z: sheet current K = M on the side
//    walls, as `kLayers` loops stacked over the height (midpoint rule);
//    a cylinder's circle is a polygon of equal area.
//  - Centripetal square (seed 001): M points from each side towards the
//    centre, perpendicular to that side; curl M = 0 inside each triangle and
//    K = M x n vanishes on the side walls, so the film equals concentric
//    square loops on its top and bottom faces with opposite currents of
//    density M (the equivalent the seed derives by Biot-Savart).
//
// Mechanics (linear elastic, small displacements): see CellKind in
// eskin/hall_config.h. A contact's footprint is a Gaussian pressure/traction
// profile of standard deviation `radius_mm`; each Film takes the part of it
// over its footprint and the first moment of that part tilts it. Contacts
// superpose (the structure is linear); the field is then the sum over all
// magnets at their displaced poses plus the constant geomagnetic field.
#pragma once

#include <vector>

#include "eskin/hall_config.h"

namespace eskin::sim {

// A straight current element from a to b (mm), current in A.
struct CurrentSegment {
  Vec3 a, b;
  double current_a;
};

// The magnet's equivalent currents in its body frame (centred at the origin,
// magnetised along body z).
std::vector<CurrentSegment> magnet_currents(const HallMagnet& m);

// B (uT) at point p (mm) of the given segments (exact Biot-Savart per segment).
Vec3 field_of_currents_ut(const std::vector<CurrentSegment>& segs, const Vec3& p);

// One contact on the skin: point of application, force on the skin (N, z up:
// pressing into the skin is fz < 0), footprint standard deviation (mm).
struct ContactLoad {
  Vec3 point_mm{0, 0, 0};
  Vec3 force_n{0, 0, 0};
  double radius_mm = 2.0;
  int cell = -1;  // Pillar/Stack cells: the cell it acts on (-1: nearest)
};

// An explicit wrench on the rigid plate (seed 002), about the plate origin.
struct PlateWrench {
  Vec3 force_n{0, 0, 0};
  Vec3 torque_nmm{0, 0, 0};
};

// A cell's displacement: translation, then a rotation (about x, then y,
// applied as Ry * Rx) about `pivot_mm` (the rest pivot).
struct CellPose {
  Vec3 translation_mm{0, 0, 0};
  double rot_x_rad = 0, rot_y_rad = 0;
  Vec3 pivot_mm{0, 0, 0};
  Vec3 force_n{0, 0, 0};  // total force the cell carries (truth)
};

// The whole skin's state under a set of loads: cell poses (truth included).
std::vector<CellPose> cell_poses(const HallConfig& h, const std::vector<ContactLoad>& contacts,
                                 const std::vector<PlateWrench>& wrenches);

// The world position of a body-frame point of a magnet at a cell pose.
Vec3 posed_point(const HallMagnet& m, const CellPose& pose, const Vec3& body);

// Precomputed equivalent currents of every magnet of a skin; evaluates B at
// the sensors for a given set of cell poses.
class HallField {
 public:
  explicit HallField(const HallConfig& h);
  // B (uT) at sensor s for the given poses (one per cell), geomagnetic field
  // included.
  Vec3 at_sensor(size_t s, const std::vector<CellPose>& poses) const;
  // Same at every sensor.
  std::vector<Vec3> at_sensors(const std::vector<CellPose>& poses) const;

 private:
  const HallConfig& h_;
  std::vector<std::vector<CurrentSegment>> body_;  // per magnet
};

// Gaussian footprint integrals over [x0, x1] for a profile centred at c with
// standard deviation s: the mass fraction and the first moment about `about`.
void gaussian_interval(double c, double s, double x0, double x1, double about, double& mass,
                       double& moment);

}  // namespace eskin::sim
