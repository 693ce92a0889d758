// Hall physics against closed forms: the equivalent-current magnets against
// the exact on-axis field of a cylinder and the far dipole field of a block;
// the centripetal film's symmetry and vanishing moment; the mechanics against
// equilibrium (forces and torques balance) and the stack's lock forces.
#include "sim/hall_physics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/hall_world.h"
#include "sim/scene.h"

namespace eskin::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

HallMagnet cylinder(double d, double h, double br) {
  HallMagnet m;
  m.shape = MagnetShape::Cylinder;
  m.size_mm = {d, d, h};
  m.remanence_t = br;
  return m;
}

// Exact on-axis field of an axially magnetised cylinder (radius R, faces at
// z = +-h/2): Bz = Br/2 * [(z + h/2)/sqrt(R^2 + (z + h/2)^2) - (z - h/2)/sqrt(...)].
double cylinder_axis_ut(double r, double h, double br, double z) {
  auto term = [&](double u) { return u / std::sqrt(r * r + u * u); };
  return br / 2 * (term(z + h / 2) - term(z - h / 2)) * 1e6;
}

TEST(HallPhysics, CylinderMatchesClosedFormOnAxis) {
  // 6 x 2 mm disc (seed 003): 8 loops over the height (midpoint rule) and a
  // 64-gon of equal area. The midpoint rule's error is h^2/(24 n^2) of the
  // second derivative: under 0.2% from 3 mm off the face; bound 0.3%.
  const HallMagnet m = cylinder(6, 2, 1.3);
  const auto segs = magnet_currents(m);
  for (double z : {-4.0, -6.0, -12.0, -20.0}) {
    const Vec3 b = field_of_currents_ut(segs, {0, 0, z});
    const double want = cylinder_axis_ut(3, 2, 1.3, z);
    EXPECT_NEAR(b[2], want, 3e-3 * std::fabs(want)) << "z " << z;
    EXPECT_NEAR(b[0], 0, 1e-9 * std::fabs(want));
    EXPECT_NEAR(b[1], 0, 1e-9 * std::fabs(want));
  }
}

TEST(HallPhysics, BoxFarFieldIsDipole) {
  // At 20x the size a block's field equals the dipole m = M V within the
  // quadrupole-free octupole term ~ (size/r)^2 ~ 0.25%; bound 1%.
  HallMagnet m;
  m.shape = MagnetShape::Box;
  m.size_mm = {4, 3, 2};
  m.remanence_t = 1.0;
  const auto segs = magnet_currents(m);
  const double mom = 1.0 / (4e-7 * kPi) * 4 * 3 * 2 * 1e-9;  // A m^2
  for (Vec3 p : {Vec3{0, 0, -80}, Vec3{80, 0, 0}, Vec3{50, 40, -50}}) {
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) * 1e-3;
    const double mz_dot = p[2] * 1e-3 / r;  // m_hat . r_hat
    Vec3 want;
    for (int k = 0; k < 3; ++k)
      want[size_t(k)] = 1e-7 * mom / (r * r * r) *
                        (3 * mz_dot * p[size_t(k)] * 1e-3 / r - (k == 2 ? 1.0 : 0.0)) * 1e6;
    const Vec3 b = field_of_currents_ut(segs, p);
    const double scale = std::sqrt(want[0] * want[0] + want[1] * want[1] + want[2] * want[2]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(b[size_t(k)], want[size_t(k)], 0.01 * scale);
  }
}

TEST(HallPhysics, CentripetalFilmHasNoMomentAndPointsAtTheCentre) {
  HallMagnet m;
  m.shape = MagnetShape::CentripetalSquare;
  m.size_mm = {20, 20, 1};
  m.remanence_t = 0.2212;
  const auto segs = magnet_currents(m);
  // On the axis, symmetry leaves only Bz.
  const Vec3 c = field_of_currents_ut(segs, {0, 0, -11.5});
  EXPECT_NEAR(c[0], 0, 1e-9 * std::fabs(c[2]));
  EXPECT_NEAR(c[1], 0, 1e-9 * std::fabs(c[2]));
  EXPECT_GT(std::fabs(c[2]), 100.0);  // hundreds of uT at the seed's distance
  // No dipole moment: far away the field falls at least like 1/r^4 (a
  // dipole would fall like 1/r^3): doubling r from 200 to 400 mm divides it
  // by more than 2^3.5.
  const double b1 = std::fabs(field_of_currents_ut(segs, {0, 0, -200})[2]);
  const double b2 = std::fabs(field_of_currents_ut(segs, {0, 0, -400})[2]);
  EXPECT_GT(b1 / b2, std::pow(2.0, 3.5));
  // Displaced along +x, Bx changes sign antisymmetrically: B(x) = -B(-x).
  const Vec3 p = field_of_currents_ut(segs, {2, 0, -11.5});
  const Vec3 q = field_of_currents_ut(segs, {-2, 0, -11.5});
  EXPECT_NEAR(p[0], -q[0], 1e-9 * std::fabs(p[0]) + 1e-9);
  EXPECT_GT(std::fabs(p[0]), 1.0);
}

TEST(HallPhysics, GaussianIntervalMassAndMoment) {
  double mass, mom;
  gaussian_interval(0, 2, -1e3, 1e3, 0, mass, mom);
  EXPECT_NEAR(mass, 1, 1e-12);
  EXPECT_NEAR(mom, 0, 1e-12);
  gaussian_interval(3, 2, -1e3, 1e3, 0, mass, mom);
  EXPECT_NEAR(mom, 3, 1e-12);  // full first moment = mean
  gaussian_interval(0, 2, 0, 1e3, 0, mass, mom);
  EXPECT_NEAR(mass, 0.5, 1e-12);
  EXPECT_NEAR(mom, 2 / std::sqrt(2 * kPi), 1e-12);  // s * phi(0)
}

Scene shipped(const char* name) {
  return load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/" + name);
}

TEST(HallPhysics, PlateBalancesForcesAndTorques) {
  // Seed 002: the three pillars' forces sum to the applied force, their
  // moments about the plate origin to the applied torque (the 6x6 solve is
  // exact: bound 1e-9 relative).
  const Scene s = shipped("hall_002_magtac.yaml");
  const HallConfig& h = s.hall.config;
  PlateWrench w{{3, -2, -15}, {80, -50, 40}};
  ContactLoad c;
  c.point_mm = {2, 1, 10};
  c.force_n = {1, 0.5, -4};
  const auto poses = cell_poses(h, {c}, {w});
  Vec3 f{0, 0, 0}, t{0, 0, 0};
  for (size_t i = 0; i < h.cells.size(); ++i) {
    const Vec3& fi = poses[i].force_n;
    const Vec3& r = h.cells[i].centre_mm;
    const Vec3 rr{r[0], r[1], 0};  // tops at the plate origin's height
    for (size_t k = 0; k < 3; ++k) f[k] += fi[k];
    t[0] += rr[1] * fi[2] - rr[2] * fi[1];
    t[1] += rr[2] * fi[0] - rr[0] * fi[2];
    t[2] += rr[0] * fi[1] - rr[1] * fi[0];
  }
  const Vec3 fw{3 + 1, -2 + 0.5, -15 - 4};
  const Vec3 tw{80 + (1 * -4 - 0 * 0.5), -50 + (0 * 1 - 2 * -4), 40 + (2 * 0.5 - 1 * 1)};
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(f[k], fw[k], 1e-9 * 20);
    EXPECT_NEAR(t[k], tw[k], 1e-9 * 100);
  }
}

TEST(HallPhysics, StackLocksAtItsRangeEnds) {
  HallCell c;
  c.kind = CellKind::Stack;
  c.layer_k_n_per_mm = {0.75, 3.3, 12};
  c.layer_travel_mm = {1.2, 1.454545, 1.35};
  const auto lock = c.stack_lock_forces_n();
  EXPECT_NEAR(lock[0], 0.9, 1e-12);
  EXPECT_NEAR(lock[1], 4.8, 1e-5);
  EXPECT_NEAR(lock[2], 16.2, 1e-12);
  // Below the first lock all three layers are in series.
  EXPECT_NEAR(c.stack_compression_mm(0.5), 0.5 * (1 / 0.75 + 1 / 3.3 + 1 / 12.0), 1e-12);
  // Between locks 1 and 2 layer 1 is solid.
  EXPECT_NEAR(c.stack_compression_mm(3), 1.2 + 3 * (1 / 3.3 + 1 / 12.0), 1e-12);
  // Past the last lock nothing moves.
  EXPECT_NEAR(c.stack_compression_mm(30), 1.2 + 1.454545 + 1.35, 1e-12);
}

// Each shipped Hall scene keeps its sensors inside the MLX90393's range over
// its whole stimulus (no saturated axis: a saturated code would be flagged
// and dropped by the decoders), and every press moves the field by far more
// than the noise.
TEST(HallPhysics, ShippedScenesStayInRangeAndRespond) {
  for (const char* name : {"hall_000_skin.yaml", "hall_001_split.yaml", "hall_002_magtac.yaml",
                           "hall_003_metamaterial.yaml"}) {
    const Scene s = shipped(name);
    const HallWorld w(s.hall);
    const HallConfig& h = w.config();
    double max_change = 0;
    std::vector<Vec3> rest;
    for (size_t i = 0; i < h.sensors.size(); ++i) rest.push_back(w.field_uT(int(i), -1));
    for (double t = 0; t < s.duration_s; t += 0.01)
      for (size_t i = 0; i < h.sensors.size(); ++i) {
        const auto b = w.field_uT(int(i), t);
        for (int a = 0; a < 3; ++a) {
          const double lim = 32767 * mlx90393::sensitivity_uT(h.mlx, a);
          EXPECT_LT(std::fabs(b[size_t(a)]), lim) << name << " sensor " << i << " axis " << a << " t " << t;
          max_change = std::max(max_change, std::fabs(b[size_t(a)] - rest[i][size_t(a)]));
        }
      }
    EXPECT_GT(max_change, 50 * h.noise_rms_ut[2]) << name;
    std::printf("%s: largest field change %.1f uT\n", name, max_change);
  }
}

}  // namespace
}  // namespace eskin::sim
