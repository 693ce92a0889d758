// eskin golden on a Hall scene: calibrate each decoding block the scene asks
// for on simulated presses, run the scene's frames through baseline and
// decoding, and score every steady frame (all active stimuli at full force)
// against the world's ground truth.
#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <memory>

#include "host/hall/hall_chain.h"
#include "host/golden/force_curve.h"
#include "host/golden/hall_baseline.h"

namespace eskin::hall {
namespace {

constexpr int kBaselineFrames = 20;  // 40 ms at OSR 0 / DIG_FILT 2, before any stimulus

double norm3(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
Eigen::VectorXd flat3(const std::vector<Vec3>& v) {
  Eigen::VectorXd x(Eigen::Index(3 * v.size()));
  for (size_t s = 0; s < v.size(); ++s)
    for (size_t k = 0; k < 3; ++k) x(Eigen::Index(3 * s + k)) = v[s][k];
  return x;
}

struct Mean {
  double sum = 0;
  int n = 0;
  void add(double v) { sum += v, ++n; }
  double get() const { return n ? sum / n : 0; }
};

std::string speed(const HallConfig& h) {
  const double us = mlx90393::conversion_us(h.mlx, mlx90393::kXYZ);
  return fmt::format("OSR {} DIG_FILT {} GAIN_SEL {} RES {}: XYZ conversion {:.0f} us, {:.0f} Hz per sensor",
                     h.mlx.osr, h.mlx.dig_filt, h.mlx.gain_sel, h.mlx.res_x, us, 1e6 / us);
}

}  // namespace

int active_stimuli(const sim::HallScene& s, double t, bool& steady) {
  int n = 0;
  steady = true;
  auto one = [&](double e) {
    if (e > 0) ++n, steady &= e >= 1.0;
  };
  for (const auto& p : s.presses) one(p.env.at(t));
  for (const auto& r : s.rolls) one(r.envelope(t));
  for (const auto& w : s.wrenches) one(w.env.at(t));
  steady &= n > 0;
  return n;
}

int run_hall_golden(const sim::HallWorld& w, double duration_s, uint64_t seed, const std::string& out_dir) {
  const HallConfig& h = w.config();
  const sim::HallScene& sc = w.scene();
  namespace fs = std::filesystem;
  fs::create_directories(out_dir);
  auto nd = fmt::output_file((fs::path(out_dir) / "hall.ndjson").string());
  fmt::print("hall: {} sensors on {} bus(es), {} magnets, {} cells; {}\n", h.sensors.size(),
             h.bus_count(), h.magnets.size(), h.cells.size(), speed(h));

  DecoupleCalibration dcal;
  WrenchCalibration wcal;
  std::vector<ForceCurve> curves;
  std::unique_ptr<golden::ContactLocator> loc;
  if (h.wants(HallDecode::Decouple)) dcal = calibrate_decouple(w, seed);
  if (h.wants(HallDecode::Wrench)) wcal = calibrate_wrench(w, seed);
  if (h.wants(HallDecode::ForceCurve)) curves = calibrate_force_curves(w, seed);
  if (h.wants(HallDecode::Locate)) {
    loc = std::make_unique<golden::ContactLocator>(calibrate_locator(w, seed));
    fmt::print("locate: {}x{} calibration scan at {} mm, {} N; Kriging table {}x{} at {:.2f} mm\n",
               loc->table_nx() / h.table_subdivision, loc->table_ny() / h.table_subdivision,
               h.scan_pitch_mm, h.scan_normal_n, loc->table_nx(), loc->table_ny(), loc->table_pitch_mm());
  }

  sim::HallSampler sampler(h, seed);
  // The baseline is captured before the first stimulus starts (at most
  // kBaselineFrames frames, at least one).
  double first = 1e300;
  for (const auto& p : sc.presses) first = std::min(first, p.env.t_start_s);
  for (const auto& r : sc.rolls) first = std::min(first, r.t_start_s);
  for (const auto& x : sc.wrenches) first = std::min(first, x.env.t_start_s);
  const int capture = std::clamp(int(first / sampler.period_s()), 1, kBaselineFrames);
  golden::HallBaseline base(h.sensors.size(), capture);
  if (h.wants(HallDecode::Decouple)) {
    // Seed 001: the geomagnetic field recorded before the film is placed.
    const std::vector<Vec3> geo(h.sensors.size(), h.geomagnetic_ut);
    std::vector<Vec3> d;
    for (int k = 0; k < capture; ++k) base.push(golden::frame_ut(sampler.sample(geo, 0), h.mlx), d);
  }
  const golden::Decoupled rest_d = golden::hall_decouple(dcal.rest_film_ut, dcal.params);

  Mean e_shear, e_normal, e_loc1, e_locm, e_roll, e_f1;
  std::array<Mean, 6> e_w;
  std::array<Mean, 3> e_range, e_range_rel;
  int frames = 0, steady_frames = 0, invalid = 0;
  std::vector<Vec3> delta;
  const double period = sampler.period_s();
  const size_t nframes = size_t(duration_s / period);
  for (size_t k = 0; k < nframes; ++k) {
    const double t = double(k) * period;
    const HallFrame f = sampler.sample(w, t);
    if (!base.push(golden::frame_ut(f, h.mlx), delta)) continue;
    ++frames;
    bool steady;
    const int n_active = active_stimuli(sc, t, steady);
    const sim::HallTruth truth = w.truth(t);
    std::string rec = fmt::format("{{\"t_s\":{:.6f},\"steady\":{}", t, steady);
    if (h.wants(HallDecode::Decouple)) {
      const golden::Decoupled d = golden::hall_decouple(delta[0], dcal.params);
      const Vec3 fe = d.valid ? golden::decoupled_force(d, rest_d, dcal.params) : Vec3{0, 0, 0};
      invalid += !d.valid;
      const Vec3 ft{truth.force_n[0], truth.force_n[1], -truth.force_n[2]};
      rec += fmt::format(",\"rx\":{:.6g},\"ry\":{:.6g},\"sz\":{:.6g},\"force_n\":[{:.4f},{:.4f},{:.4f}],\"truth_n\":[{:.4f},{:.4f},{:.4f}]",
                         d.rx, d.ry, d.sz, fe[0], fe[1], fe[2], ft[0], ft[1], ft[2]);
      if (steady && d.valid) {
        e_shear.add(std::fabs(fe[0] - ft[0]) / dcal.shear_fs_n);
        e_shear.add(std::fabs(fe[1] - ft[1]) / dcal.shear_fs_n);
        e_normal.add(std::fabs(fe[2] - ft[2]) / dcal.normal_fs_n);
      }
    }
    if (h.wants(HallDecode::Wrench)) {
      golden::Vec9 b;
      for (int i = 0; i < 9; ++i) b(i) = delta[size_t(i / 3)][size_t(i % 3)];
      const golden::Vec6 we = golden::ft_apply(wcal.c, b);
      golden::Vec6 wt;
      wt << truth.force_n[0], truth.force_n[1], truth.force_n[2], truth.torque_nmm[0], truth.torque_nmm[1],
          truth.torque_nmm[2];
      rec += fmt::format(",\"wrench\":[{}],\"truth\":[{}]", fmt::join(we.data(), we.data() + 6, ","),
                         fmt::join(wt.data(), wt.data() + 6, ","));
      if (steady)
        for (int a = 0; a < 6; ++a) e_w[size_t(a)].add(std::fabs(we(a) - wt(a)) / wcal.full_scale(a));
    }
    if (h.wants(HallDecode::ForceCurve)) {
      std::vector<double> fe;
      size_t ci = 0;
      for (size_t i = 0; i < h.cells.size(); ++i) {
        if (h.cells[i].kind != CellKind::Stack) continue;
        const double d = norm3(delta[i]);
        fe.push_back(golden::force_curve_apply(curves[ci++], d));
        const double ft = -truth.cells[i].force_n[2];
        if (steady && ft > 0) {
          const auto lock = h.cells[i].stack_lock_forces_n();
          const size_t r = size_t(std::lower_bound(lock.begin(), lock.end(), ft) - lock.begin());
          if (r < 3) {
            e_range[r].add(std::fabs(fe.back() - ft) / lock[r]);
            e_range_rel[r].add(std::fabs(fe.back() - ft) / ft);
          }
        }
      }
      rec += fmt::format(",\"cell_force_n\":[{:.4f}]", fmt::join(fe, ","));
    }
    if (loc) {
      const auto found = loc->locate(flat3(delta), std::max(1, n_active), 0.05);
      rec += ",\"contacts\":[";
      for (size_t i = 0; i < found.size(); ++i)
        rec += fmt::format("{}[{:.2f},{:.2f},{:.3f}]", i ? "," : "", found[i].x_mm, found[i].y_mm, found[i].force_n);
      rec += "]";
      if (steady) {
        // Each true contact against the nearest found one.
        const bool rolling = !sc.rolls.empty() && sc.rolls[0].envelope(t) > 0;
        for (const auto& c : truth.contacts) {
          double best = 1e300, fbest = 0;
          for (const auto& g : found) {
            const double e = std::hypot(g.x_mm - c.point_mm[0], g.y_mm - c.point_mm[1]);
            if (e < best) best = e, fbest = g.force_n;
          }
          if (rolling) e_roll.add(best);
          else if (truth.contacts.size() == 1) e_loc1.add(best), e_f1.add(std::fabs(fbest + c.force_n[2]) / -c.force_n[2]);
          else e_locm.add(best);
        }
      }
    }
    nd.print("{}}}\n", rec);
    steady_frames += steady;
  }

  fmt::print("frames: {} decoded ({} steady, scored against ground truth), period {:.3f} ms\n", frames,
             steady_frames, period * 1e3);
  if (h.wants(HallDecode::Decouple))
    fmt::print("decouple (seed 001): mean |error| shear {:.2f}% of {:.2f} N, normal {:.2f}% of {:.2f} N; "
               "{} frames out of range; k1 {} c1 {:.1f} uT, k2 {} c2 {:.1f} uT\n",
               100 * e_shear.get(), dcal.shear_fs_n, 100 * e_normal.get(), dcal.normal_fs_n, invalid,
               dcal.params.k1, dcal.params.c1_ut, dcal.params.k2, dcal.params.c2_ut);
  if (h.wants(HallDecode::Wrench)) {
    double avg = 0;
    const char* names[] = {"Fx", "Fy", "Fz", "Tx", "Ty", "Tz"};
    fmt::print("wrench (seed 002, C 6x9 from {} presses): mean |error| in % of calibration range:", wcal.presses);
    for (int a = 0; a < 6; ++a) fmt::print(" {} {:.2f}%", names[a], 100 * e_w[size_t(a)].get()), avg += e_w[size_t(a)].get() / 6;
    fmt::print("; average {:.2f}%\n", 100 * avg);
  }
  if (h.wants(HallDecode::ForceCurve)) {
    const char* names[] = {"range 1 (0..0.9 N)", "range 2 (0.9..4.8 N)", "range 3 (4.8..16.2 N)"};
    for (int r = 0; r < 3; ++r)
      fmt::print("force curve (seed 003) {}: {} frames, mean |error| {:.2f}% of the range's top, {:.2f}% of the force\n",
                 names[r], e_range[size_t(r)].n, 100 * e_range[size_t(r)].get(), 100 * e_range_rel[size_t(r)].get());
  }
  if (loc)
    fmt::print("locate (seed 000): single presses {:.2f} mm mean error ({} frames), force {:.1f}%; "
               "multi-point {:.2f} mm ({}); rolling ball {:.2f} mm ({})\n",
               e_loc1.get(), e_loc1.n, 100 * e_f1.get(), e_locm.get(), e_locm.n, e_roll.get(), e_roll.n);
  fmt::print("hall outputs written to {}/hall.ndjson\n", out_dir);
  return 0;
}

}  // namespace eskin::hall
