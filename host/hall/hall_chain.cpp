#include "host/hall/hall_chain.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "host/golden/force_curve.h"
#include "host/golden/hall_baseline.h"

namespace eskin::hall {
namespace {

constexpr int kBaselineFrames = 20;  // 40 ms at OSR 0 / DIG_FILT 2, before any stimulus
constexpr int kCalFrames = 8;        // frames averaged per calibration press

std::vector<Vec3> minus(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  std::vector<Vec3> d(a.size());
  for (size_t s = 0; s < a.size(); ++s)
    for (size_t k = 0; k < 3; ++k) d[s][k] = a[s][k] - b[s][k];
  return d;
}

Eigen::VectorXd flat(const std::vector<Vec3>& v) {
  Eigen::VectorXd x(Eigen::Index(3 * v.size()));
  for (size_t s = 0; s < v.size(); ++s)
    for (size_t k = 0; k < 3; ++k) x(Eigen::Index(3 * s + k)) = v[s][k];
  return x;
}

double norm3(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

sim::ContactLoad press_at(const sim::HallWorld& w, double x, double y, Vec3 f, double radius, int cell = -1) {
  sim::ContactLoad c;
  c.point_mm = {x, y, w.scene().surface_z_mm()};
  c.force_n = f;
  c.radius_mm = radius;
  c.cell = cell;
  return c;
}

// The geomagnetic field alone at every sensor (the seed-001 baseline is
// recorded before the film is put in place).
std::vector<Vec3> geomagnetic(const sim::HallWorld& w) {
  return std::vector<Vec3>(w.config().sensors.size(), w.config().geomagnetic_ut);
}

std::vector<Vec3> mean_of(sim::HallSampler& s, const std::vector<Vec3>& field, const mlx90393::Config& c,
                          int frames) {
  std::vector<Vec3> sum(field.size(), Vec3{0, 0, 0});
  for (int k = 0; k < frames; ++k) {
    const auto f = golden::frame_ut(s.sample(field, 0), c);
    for (size_t i = 0; i < f.size(); ++i)
      for (size_t a = 0; a < 3; ++a) sum[i][a] += f[i][a] / frames;
  }
  return sum;
}

}  // namespace

void apply_speed(HallConfig& h, int osr, int dig_filt) {
  mlx90393::Config to = h.mlx;
  if (osr >= 0) to.osr = osr;
  if (dig_filt >= 0) to.dig_filt = dig_filt;
  mlx90393::validate(to, "--hall-osr/--hall-dig-filt");
  h.noise_rms_ut = scaled_noise_ut(h.noise_rms_ut, h.mlx, to);
  h.mlx = to;
}

std::vector<Vec3> mean_field(const sim::HallWorld& w, sim::HallSampler& s,
                             const std::vector<sim::ContactLoad>& contacts,
                             const std::vector<sim::PlateWrench>& plate, int frames) {
  return mean_of(s, w.fields_under(contacts, plate), w.config().mlx, frames);
}

DecoupleCalibration calibrate_decouple(const sim::HallWorld& w, uint64_t seed) {
  const HallConfig& h = w.config();
  sim::HallSampler s(h, seed + 101);
  const auto geo = mean_of(s, geomagnetic(w), h.mlx, kCalFrames);
  DecoupleCalibration cal;
  const HallCell& cell = h.cells[0];
  // The seed's working range: 0..3 mm normal, +-3 mm shear.
  cal.normal_fs_n = 3.0 * cell.k_normal_n_per_mm;
  cal.shear_fs_n = 3.0 * cell.k_shear_n_per_mm;
  cal.rest_film_ut = minus(mean_field(w, s, {}, {}, kCalFrames), geo)[0];
  std::vector<golden::DecoupleSample> samples;
  for (int n = 1; n <= 6; ++n)
    for (int i = -3; i <= 3; ++i)
      for (int j = -3; j <= 3; ++j) {
        const Vec3 f{cal.shear_fs_n * i / 3, cal.shear_fs_n * j / 3, cal.normal_fs_n * n / 6};
        const auto c = press_at(w, cell.centre_mm[0], cell.centre_mm[1], {f[0], f[1], -f[2]}, 3.0, 0);
        samples.push_back({minus(mean_field(w, s, {c}, {}, kCalFrames), geo)[0], f});
      }
  cal.params = golden::fit_decouple(samples, cal.rest_film_ut);
  return cal;
}

golden::Vec6 wrench_calibration_range() {
  golden::Vec6 r;
  r << 8, 8, 24, 150, 150, 120;
  return r;
}

WrenchPresses simulate_wrench_presses(const sim::HallWorld& w, uint64_t seed, int presses) {
  sim::HallSampler s(w.config(), seed + 202);
  std::mt19937_64 rng(seed + 303);
  std::uniform_real_distribution<double> u(-1, 1);
  const golden::Vec6 range = wrench_calibration_range();
  const auto rest = mean_field(w, s, {}, {}, kCalFrames);
  WrenchPresses p;
  for (int k = 0; k < presses; ++k) {
    golden::Vec6 x;
    for (int a = 0; a < 6; ++a) x(a) = u(rng) * range(a);
    x(2) = -std::fabs(x(2));  // pressing, never pulling
    const sim::PlateWrench pw{{x(0), x(1), x(2)}, {x(3), x(4), x(5)}};
    p.db_ut.push_back(flat(minus(mean_field(w, s, {}, {pw}, kCalFrames), rest)));
    p.wrench.push_back(x);
  }
  return p;
}

WrenchCalibration calibrate_wrench(const sim::HallWorld& w, uint64_t seed, int presses) {
  const WrenchPresses p = simulate_wrench_presses(w, seed, presses);
  WrenchCalibration cal;
  cal.presses = presses;
  cal.full_scale = wrench_calibration_range();
  cal.c = golden::ft_fit(p.db_ut, p.wrench);
  return cal;
}

WrenchCalibration calibrate_wrench_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<golden::Vec9> db;
  std::vector<golden::Vec6> wr;
  std::string line;
  int lineno = 0;
  WrenchCalibration cal;
  cal.full_scale.setZero();
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty() || line[0] == '#' || std::isalpha(static_cast<unsigned char>(line[0]))) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ss(line);
    std::vector<double> v;
    double x;
    while (ss >> x) v.push_back(x);
    if (v.size() != 15 || !ss.eof())
      throw std::runtime_error(fmt::format("{}:{}: expected 15 numbers (b1x..b3z uT, fx fy fz N, tx ty tz N*mm), got {}",
                                           path, lineno, v.size()));
    golden::Vec9 b;
    golden::Vec6 f;
    for (int k = 0; k < 9; ++k) b(k) = v[size_t(k)];
    for (int k = 0; k < 6; ++k) f(k) = v[size_t(9 + k)], cal.full_scale(k) = std::max(cal.full_scale(k), std::fabs(f(k)));
    db.push_back(b);
    wr.push_back(f);
  }
  cal.c = golden::ft_fit(db, wr);
  cal.presses = int(db.size());
  return cal;
}

std::vector<ForceCurve> calibrate_force_curves(const sim::HallWorld& w, uint64_t seed, int per_range) {
  const HallConfig& h = w.config();
  sim::HallSampler s(h, seed + 404);
  const auto rest = mean_field(w, s, {}, {}, kCalFrames);
  std::vector<ForceCurve> curves;
  for (size_t i = 0; i < h.cells.size(); ++i) {
    const HallCell& c = h.cells[i];
    if (c.kind != CellKind::Stack) continue;
    const auto lock = c.stack_lock_forces_n();
    std::vector<double> db, f;
    for (double force = 0; force <= lock.back() + 1e-9; force += lock.back() / 160) {
      const auto cl = press_at(w, c.centre_mm[0], c.centre_mm[1], {0, 0, -force}, 5.0, int(i));
      const auto b = mean_field(w, s, {cl}, {}, kCalFrames);
      db.push_back(norm3({b[i][0] - rest[i][0], b[i][1] - rest[i][1], b[i][2] - rest[i][2]}));
      f.push_back(force);
    }
    curves.push_back(golden::fit_force_curve(db, f, lock, per_range));
  }
  return curves;
}

golden::ContactLocator calibrate_locator(const sim::HallWorld& w, uint64_t seed) {
  const HallConfig& h = w.config();
  sim::HallSampler s(h, seed + 505);
  const auto rest = mean_field(w, s, {}, {}, kCalFrames);
  golden::ScanGrid g;
  g.pitch_mm = h.scan_pitch_mm;
  g.nx = int(std::lround((h.area_mm[2] - h.area_mm[0]) / g.pitch_mm));
  g.ny = int(std::lround((h.area_mm[3] - h.area_mm[1]) / g.pitch_mm));
  g.x0 = h.area_mm[0] + g.pitch_mm / 2;
  g.y0 = h.area_mm[1] + g.pitch_mm / 2;
  g.force_n = h.scan_normal_n;
  std::vector<Eigen::VectorXd> scan;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      // The 4 mm spherical indenter of the seed's scans.
      const auto c = press_at(w, g.x0 + i * g.pitch_mm, g.y0 + j * g.pitch_mm, {0, 0, -g.force_n}, 2.0);
      scan.push_back(flat(minus(mean_field(w, s, {c}, {}, 2), rest)));
    }
  return golden::ContactLocator(g, scan, h.table_subdivision);
}

}  // namespace eskin::hall
