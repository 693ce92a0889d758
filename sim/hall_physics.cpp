#include "sim/hall_physics.h"

#include <Eigen/Dense>

#include <cmath>
#include <limits>

namespace eskin::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMu0 = 4e-7 * kPi;  // T*m/A
constexpr int kLayers = 8;           // loops stacked over a Box/Cylinder height
constexpr int kPolygon = 64;         // sides of a Cylinder's loops
constexpr int kRings = 32;           // square loops per face of a centripetal film

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// A closed polygon loop (vertices in order, counter-clockwise seen from +z for
// positive current) appended as segments.
void add_loop(std::vector<CurrentSegment>& out, const std::vector<Vec3>& v, double current) {
  for (size_t i = 0; i < v.size(); ++i) out.push_back({v[i], v[(i + 1) % v.size()], current});
}

std::vector<Vec3> rectangle(double hx, double hy, double z) {
  return {{-hx, -hy, z}, {hx, -hy, z}, {hx, hy, z}, {-hx, hy, z}};
}

// R = Ry(b) * Rx(a).
Eigen::Matrix3d rotation(double a, double b) {
  return (Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d ev(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vec3 av(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d s;
  s << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return s;
}

}  // namespace

std::vector<CurrentSegment> magnet_currents(const HallMagnet& m) {
  std::vector<CurrentSegment> out;
  const double magnetisation = m.remanence_t / kMu0;  // A/m
  const double h = m.size_mm[2];
  switch (m.shape) {
    case MagnetShape::Box:
    case MagnetShape::Cylinder: {
      const double current = magnetisation * h * 1e-3 / kLayers;  // A per loop
      for (int k = 0; k < kLayers; ++k) {
        const double z = -h / 2 + (k + 0.5) * h / kLayers;
        if (m.shape == MagnetShape::Box) {
          add_loop(out, rectangle(m.size_mm[0] / 2, m.size_mm[1] / 2, z), current);
        } else {
          // Polygon of the circle's area, so the loop's moment is exact.
          const double r = m.size_mm[0] / 2 *
                           std::sqrt(2 * kPi / (kPolygon * std::sin(2 * kPi / kPolygon)));
          std::vector<Vec3> v;
          for (int i = 0; i < kPolygon; ++i) {
            const double t = 2 * kPi * i / kPolygon;
            v.push_back({r * std::cos(t), r * std::sin(t), z});
          }
          add_loop(out, v, current);
        }
      }
      break;
    }
    case MagnetShape::CentripetalSquare: {
      // Inward in-plane M: K = M x n is counter-clockwise on the top face and
      // clockwise on the bottom face; rings at the midpoints of kRings bands.
      const double half = m.size_mm[0] / 2;
      const double current = magnetisation * half * 1e-3 / kRings;
      for (int k = 0; k < kRings; ++k) {
        const double s = (k + 0.5) * half / kRings;
        add_loop(out, rectangle(s, s, h / 2), current);
        add_loop(out, rectangle(s, s, -h / 2), -current);
      }
      break;
    }
  }
  return out;
}

Vec3 field_of_currents_ut(const std::vector<CurrentSegment>& segs, const Vec3& p) {
  // mu0/(4 pi) * I * geometry[1/mm]: 1e-7 T*m/A * 1e3 /m-per-/mm = 1e-4 T = 100 uT.
  Vec3 b{0, 0, 0};
  for (const auto& s : segs) {
    const Vec3 a = sub(p, s.a), c = sub(p, s.b);
    const double na = norm(a), nc = norm(c);
    const double den = na * nc * (na * nc + dot(a, c));
    if (den < 1e-18) continue;  // on the segment's line: no finite field
    const double k = 100.0 * s.current_a * (na + nc) / den;
    const Vec3 x = cross(a, c);
    b[0] += k * x[0], b[1] += k * x[1], b[2] += k * x[2];
  }
  return b;
}

void gaussian_interval(double c, double s, double x0, double x1, double about, double& mass,
                       double& moment) {
  const double u0 = (x0 - c) / s, u1 = (x1 - c) / s;
  auto phi = [](double u) { return std::exp(-0.5 * u * u) / std::sqrt(2 * kPi); };
  mass = 0.5 * (std::erf(u1 / std::sqrt(2.0)) - std::erf(u0 / std::sqrt(2.0)));
  // Integral of (x - about) over the profile: s*(phi(u0) - phi(u1)) + (c - about)*mass.
  moment = s * (phi(u0) - phi(u1)) + (c - about) * mass;
}

namespace {

Vec3 pivot_of(const HallCell& c) {
  Vec3 p = c.centre_mm;
  if (c.kind == CellKind::Pillar) p[2] -= c.pillar_mm;
  return p;
}

void load_film(const HallCell& c, const ContactLoad& l, CellPose& pose) {
  double mx, momx, my, momy;
  gaussian_interval(l.point_mm[0], l.radius_mm, c.centre_mm[0] - c.footprint_mm[0] / 2,
                    c.centre_mm[0] + c.footprint_mm[0] / 2, c.centre_mm[0], mx, momx);
  gaussian_interval(l.point_mm[1], l.radius_mm, c.centre_mm[1] - c.footprint_mm[1] / 2,
                    c.centre_mm[1] + c.footprint_mm[1] / 2, c.centre_mm[1], my, momy);
  const double frac = mx * my;
  if (frac <= 0) return;
  const Vec3 f{l.force_n[0] * frac, l.force_n[1] * frac, l.force_n[2] * frac};
  pose.force_n = add(pose.force_n, f);
  pose.translation_mm[0] += f[0] / c.k_shear_n_per_mm;
  pose.translation_mm[1] += f[1] / c.k_shear_n_per_mm;
  pose.translation_mm[2] += f[2] / c.k_normal_n_per_mm;
  // Rigid film on a uniform foundation: tilt stiffness k * a^2 / 12 per axis.
  const double ktx = c.k_normal_n_per_mm * c.footprint_mm[0] * c.footprint_mm[0] / 12;
  const double kty = c.k_normal_n_per_mm * c.footprint_mm[1] * c.footprint_mm[1] / 12;
  const double slope_x = l.force_n[2] * momx * my / ktx;  // dz/dx
  const double slope_y = l.force_n[2] * mx * momy / kty;  // dz/dy
  pose.rot_y_rad += -slope_x;  // Ry(b): dz/dx = -b
  pose.rot_x_rad += slope_y;   // Rx(a): dz/dy = +a
}

// Pillar under a force at its top: z by the normal force, tilt about the pivot
// by the shear force's moment.
void set_pillar(const HallCell& c, const Vec3& f, CellPose& pose) {
  pose.force_n = f;
  pose.translation_mm = {0, 0, f[2] / c.k_normal_n_per_mm};
  pose.rot_y_rad = c.pillar_mm * f[0] / c.k_tilt_nmm_per_rad;   // top moves +x
  pose.rot_x_rad = -c.pillar_mm * f[1] / c.k_tilt_nmm_per_rad;  // top moves +y
}

void set_stack(const HallCell& c, const Vec3& f, CellPose& pose) {
  pose.force_n = f;
  pose.translation_mm = {0, 0, -c.stack_compression_mm(-f[2])};
}

size_t nearest_cell(const HallConfig& h, const ContactLoad& l) {
  if (l.cell >= 0) return size_t(l.cell);
  size_t best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < h.cells.size(); ++i) {
    const double dx = h.cells[i].centre_mm[0] - l.point_mm[0];
    const double dy = h.cells[i].centre_mm[1] - l.point_mm[1];
    if (h.cells[i].kind != CellKind::Film && dx * dx + dy * dy < bd) bd = dx * dx + dy * dy, best = i;
  }
  return best;
}

// Rigid plate on all Pillar cells: solve the 6x6 stiffness system for the
// plate's translation t and rotation phi about the centroid o of the tops;
// each pillar top moves t + phi x r_i and carries K_i of that.
void solve_plate(const HallConfig& h, const std::vector<ContactLoad>& contacts,
                 const std::vector<PlateWrench>& wrenches, std::vector<CellPose>& poses) {
  std::vector<size_t> pillars;
  Eigen::Vector3d o = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < h.cells.size(); ++i)
    if (h.cells[i].kind == CellKind::Pillar) pillars.push_back(i), o += ev(h.cells[i].centre_mm);
  if (pillars.empty()) return;
  o /= double(pillars.size());
  Eigen::Matrix<double, 6, 1> w = Eigen::Matrix<double, 6, 1>::Zero();
  for (const auto& c : contacts) {
    const Eigen::Vector3d f = ev(c.force_n);
    w.head<3>() += f;
    w.tail<3>() += (ev(c.point_mm) - o).cross(f);
  }
  for (const auto& x : wrenches) w.head<3>() += ev(x.force_n), w.tail<3>() += ev(x.torque_nmm);
  Eigen::Matrix<double, 6, 6> k = Eigen::Matrix<double, 6, 6>::Zero();
  std::vector<Eigen::Matrix3d> ki;
  for (size_t i : pillars) {
    const HallCell& c = h.cells[i];
    const double ks = c.k_tilt_nmm_per_rad / (c.pillar_mm * c.pillar_mm);
    Eigen::Matrix3d kk = Eigen::Vector3d(ks, ks, c.k_normal_n_per_mm).asDiagonal();
    const Eigen::Matrix3d s = skew(ev(c.centre_mm) - o);
    // d = t - S phi; f = K d; moment = S f.
    k.block<3, 3>(0, 0) += kk;
    k.block<3, 3>(0, 3) += -kk * s;
    k.block<3, 3>(3, 0) += s * kk;
    k.block<3, 3>(3, 3) += -s * kk * s;
    ki.push_back(kk);
  }
  const Eigen::Matrix<double, 6, 1> u = k.fullPivLu().solve(w);
  for (size_t n = 0; n < pillars.size(); ++n) {
    const HallCell& c = h.cells[pillars[n]];
    const Eigen::Vector3d d = u.head<3>() - skew(ev(c.centre_mm) - o) * u.tail<3>();
    set_pillar(c, av(ki[n] * d), poses[pillars[n]]);
  }
}

}  // namespace

std::vector<CellPose> cell_poses(const HallConfig& h, const std::vector<ContactLoad>& contacts,
                                 const std::vector<PlateWrench>& wrenches) {
  std::vector<CellPose> poses(h.cells.size());
  for (size_t i = 0; i < h.cells.size(); ++i) poses[i].pivot_mm = pivot_of(h.cells[i]);
  for (size_t i = 0; i < h.cells.size(); ++i)
    if (h.cells[i].kind == CellKind::Film)
      for (const auto& l : contacts) load_film(h.cells[i], l, poses[i]);
  if (h.rigid_plate) {
    solve_plate(h, contacts, wrenches, poses);
    return poses;
  }
  // Without a plate each contact acts on one Pillar/Stack cell.
  std::vector<Vec3> f(h.cells.size(), Vec3{0, 0, 0});
  bool any = false;
  for (const auto& c : h.cells) any |= c.kind != CellKind::Film;
  if (!any) return poses;
  for (const auto& l : contacts) {
    const size_t i = nearest_cell(h, l);
    f[i] = add(f[i], l.force_n);
  }
  for (size_t i = 0; i < h.cells.size(); ++i) {
    if (h.cells[i].kind == CellKind::Pillar) set_pillar(h.cells[i], f[i], poses[i]);
    if (h.cells[i].kind == CellKind::Stack) set_stack(h.cells[i], f[i], poses[i]);
  }
  return poses;
}

Vec3 posed_point(const HallMagnet& m, const CellPose& pose, const Vec3& body) {
  const Eigen::Vector3d rest = ev(m.centre_mm) + ev(body);
  const Eigen::Vector3d piv = ev(pose.pivot_mm);
  return av(piv + ev(pose.translation_mm) + rotation(pose.rot_x_rad, pose.rot_y_rad) * (rest - piv));
}

HallField::HallField(const HallConfig& h) : h_(h) {
  for (const auto& m : h.magnets) body_.push_back(magnet_currents(m));
}

Vec3 HallField::at_sensor(size_t s, const std::vector<CellPose>& poses) const {
  const Eigen::Vector3d p = ev(h_.sensors[s].position_mm);
  Eigen::Vector3d b = ev(h_.geomagnetic_ut);
  for (size_t i = 0; i < h_.magnets.size(); ++i) {
    const HallMagnet& m = h_.magnets[i];
    const CellPose& pose = poses[size_t(m.cell)];
    const Eigen::Matrix3d r = rotation(pose.rot_x_rad, pose.rot_y_rad);
    const Eigen::Vector3d piv = ev(pose.pivot_mm);
    // Sensor into the magnet's body frame, field back into the world frame.
    const Eigen::Vector3d body =
        r.transpose() * (p - piv - ev(pose.translation_mm)) + piv - ev(m.centre_mm);
    b += r * ev(field_of_currents_ut(body_[i], av(body)));
  }
  return av(b);
}

std::vector<Vec3> HallField::at_sensors(const std::vector<CellPose>& poses) const {
  std::vector<Vec3> out;
  for (size_t s = 0; s < h_.sensors.size(); ++s) out.push_back(at_sensor(s, poses));
  return out;
}

}  // namespace eskin::sim
