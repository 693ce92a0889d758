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

namespace {

// Each decoding block the scene asks for, calibrated on its own skin.
struct HallGoldenCal {
  DecoupleCalibration dcal;
  WrenchCalibration wcal;
  std::vector<ForceCurve> curves;
  std::unique_ptr<golden::ContactLocator> loc;
  golden::Decoupled rest_d;
};

// The errors of the steady frames against the truth.
struct HallGoldenScores {
  Mean e_shear, e_normal, e_loc1, e_locm, e_roll, e_f1;
  std::array<Mean, 6> e_w;
  std::array<Mean, 3> e_range, e_range_rel;
  int frames = 0, steady_frames = 0, invalid = 0;
};

// One frame being decoded: its time, the truth and the field change at
// each sensor.
struct HallGoldenFrame {
  double t;
  bool steady;
  int n_active;
  sim::HallTruth truth;
  const std::vector<Vec3>& delta;
};

void calibrate_blocks(const sim::HallWorld& w, uint64_t seed, HallGoldenCal& c) {
  const HallConfig& h = w.config();
  if (h.wants(HallDecode::Decouple)) c.dcal = calibrate_decouple(w, seed);
  if (h.wants(HallDecode::Wrench)) c.wcal = calibrate_wrench(w, seed);
  if (h.wants(HallDecode::ForceCurve)) c.curves = calibrate_force_curves(w, seed);
  if (h.wants(HallDecode::Locate)) {
    c.loc = std::make_unique<golden::ContactLocator>(calibrate_locator(w, seed));
    const golden::ContactLocator& loc = *c.loc;
    fmt::print("locate: {}x{} calibration scan at {} mm, {} N; Kriging table {}x{} at {:.2f} mm\n",
               loc.table_nx() / h.table_subdivision, loc.table_ny() / h.table_subdivision,
               h.scan_pitch_mm, h.scan_normal_n, loc.table_nx(), loc.table_ny(), loc.table_pitch_mm());
  }
  c.rest_d = golden::hall_decouple(c.dcal.rest_film_ut, c.dcal.params);
}

// The baseline is captured before the first stimulus starts (at most
// kBaselineFrames frames, at least one); seed 001 records the geomagnetic
// field before the film is placed.
golden::HallBaseline capture_baseline(const HallConfig& h, const sim::HallScene& sc,
                                      sim::HallSampler& sampler) {
  double first = 1e300;
  for (const auto& p : sc.presses) first = std::min(first, p.env.t_start_s);
  for (const auto& r : sc.rolls) first = std::min(first, r.t_start_s);
  for (const auto& x : sc.wrenches) first = std::min(first, x.env.t_start_s);
  const int capture = std::clamp(int(first / sampler.period_s()), 1, kBaselineFrames);
  golden::HallBaseline base(h.sensors.size(), capture);
  if (h.wants(HallDecode::Decouple)) {
    const std::vector<Vec3> geo(h.sensors.size(), h.geomagnetic_ut);
    std::vector<Vec3> d;
    for (int k = 0; k < capture; ++k) base.push(golden::frame_ut(sampler.sample(geo, 0), h.mlx), d);
  }
  return base;
}

// Seed 001: (Rx, Ry, Sz) and the force; the frame's NDJSON fields.
std::string decouple_frame(const HallGoldenCal& c, const HallGoldenFrame& f, HallGoldenScores& s) {
  const auto& dcal = c.dcal;
  const golden::Decoupled d = golden::hall_decouple(f.delta[0], dcal.params);
  const Vec3 fe = d.valid ? golden::decoupled_force(d, c.rest_d, dcal.params) : Vec3{0, 0, 0};
  s.invalid += !d.valid;
  const Vec3 ft{f.truth.force_n[0], f.truth.force_n[1], -f.truth.force_n[2]};
  if (f.steady && d.valid) {
    s.e_shear.add(std::fabs(fe[0] - ft[0]) / dcal.shear_fs_n);
    s.e_shear.add(std::fabs(fe[1] - ft[1]) / dcal.shear_fs_n);
    s.e_normal.add(std::fabs(fe[2] - ft[2]) / dcal.normal_fs_n);
  }
  return fmt::format(",\"rx\":{:.6g},\"ry\":{:.6g},\"sz\":{:.6g},\"force_n\":[{:.4f},{:.4f},{:.4f}],\"truth_n\":[{:.4f},{:.4f},{:.4f}]",
                     d.rx, d.ry, d.sz, fe[0], fe[1], fe[2], ft[0], ft[1], ft[2]);
}

// Seed 002: the wrench through C; the frame's NDJSON fields.
std::string wrench_frame(const HallGoldenCal& c, const HallGoldenFrame& f, HallGoldenScores& s) {
  golden::Vec9 b;
  for (int i = 0; i < 9; ++i) b(i) = f.delta[size_t(i / 3)][size_t(i % 3)];
  const golden::Vec6 we = golden::ft_apply(c.wcal.c, b);
  golden::Vec6 wt;
  wt << f.truth.force_n[0], f.truth.force_n[1], f.truth.force_n[2], f.truth.torque_nmm[0],
      f.truth.torque_nmm[1], f.truth.torque_nmm[2];
  if (f.steady)
    for (int a = 0; a < 6; ++a) s.e_w[size_t(a)].add(std::fabs(we(a) - wt(a)) / c.wcal.full_scale(a));
  return fmt::format(",\"wrench\":[{}],\"truth\":[{}]", fmt::join(we.data(), we.data() + 6, ","),
                     fmt::join(wt.data(), wt.data() + 6, ","));
}

// Seed 003: each Stack cell's force through its curve; the frame's NDJSON
// field.
std::string curve_frame(const HallConfig& h, const HallGoldenCal& c, const HallGoldenFrame& f,
                        HallGoldenScores& s) {
  std::vector<double> fe;
  size_t ci = 0;
  for (size_t i = 0; i < h.cells.size(); ++i) {
    if (h.cells[i].kind != CellKind::Stack) continue;
    const double d = norm3(f.delta[i]);
    fe.push_back(golden::force_curve_apply(c.curves[ci++], d));
    const double ft = -f.truth.cells[i].force_n[2];
    if (f.steady && ft > 0) {
      const auto lock = h.cells[i].stack_lock_forces_n();
      const size_t r = size_t(std::lower_bound(lock.begin(), lock.end(), ft) - lock.begin());
      if (r < 3) {
        s.e_range[r].add(std::fabs(fe.back() - ft) / lock[r]);
        s.e_range_rel[r].add(std::fabs(fe.back() - ft) / ft);
      }
    }
  }
  return fmt::format(",\"cell_force_n\":[{:.4f}]", fmt::join(fe, ","));
}

// Seed 000: the contacts found, each true contact against the nearest
// found one; the frame's NDJSON field.
std::string locate_frame(const sim::HallScene& sc, const HallGoldenCal& c, const HallGoldenFrame& f,
                         HallGoldenScores& s) {
  const auto found = c.loc->locate(flat3(f.delta), std::max(1, f.n_active), 0.05);
  std::string rec = ",\"contacts\":[";
  for (size_t i = 0; i < found.size(); ++i)
    rec += fmt::format("{}[{:.2f},{:.2f},{:.3f}]", i ? "," : "", found[i].x_mm, found[i].y_mm, found[i].force_n);
  rec += "]";
  if (!f.steady) return rec;
  const bool rolling = !sc.rolls.empty() && sc.rolls[0].envelope(f.t) > 0;
  for (const auto& tc : f.truth.contacts) {
    double best = 1e300, fbest = 0;
    for (const auto& g : found) {
      const double e = std::hypot(g.x_mm - tc.point_mm[0], g.y_mm - tc.point_mm[1]);
      if (e < best) best = e, fbest = g.force_n;
    }
    if (rolling) s.e_roll.add(best);
    else if (f.truth.contacts.size() == 1) s.e_loc1.add(best), s.e_f1.add(std::fabs(fbest + tc.force_n[2]) / -tc.force_n[2]);
    else s.e_locm.add(best);
  }
  return rec;
}

// Every frame of the scene through baseline and the decoding blocks, one
// NDJSON record each.
void decode_frames(const sim::HallWorld& w, double duration_s, sim::HallSampler& sampler,
                   golden::HallBaseline& base, const HallGoldenCal& c, fmt::ostream& nd,
                   HallGoldenScores& s) {
  const HallConfig& h = w.config();
  const sim::HallScene& sc = w.scene();
  std::vector<Vec3> delta;
  const double period = sampler.period_s();
  const size_t nframes = size_t(duration_s / period);
  for (size_t k = 0; k < nframes; ++k) {
    const double t = double(k) * period;
    const HallFrame fr = sampler.sample(w, t);
    if (!base.push(golden::frame_ut(fr, h.mlx), delta)) continue;
    ++s.frames;
    bool steady;
    const int n_active = active_stimuli(sc, t, steady);
    const HallGoldenFrame f{t, steady, n_active, w.truth(t), delta};
    std::string rec = fmt::format("{{\"t_s\":{:.6f},\"steady\":{}", t, steady);
    if (h.wants(HallDecode::Decouple)) rec += decouple_frame(c, f, s);
    if (h.wants(HallDecode::Wrench)) rec += wrench_frame(c, f, s);
    if (h.wants(HallDecode::ForceCurve)) rec += curve_frame(h, c, f, s);
    if (c.loc) rec += locate_frame(sc, c, f, s);
    nd.print("{}}}\n", rec);
    s.steady_frames += steady;
  }
}

// Each block's mean errors on stdout.
void print_scores(const HallConfig& h, const HallGoldenCal& c, const HallGoldenScores& s,
                  double period) {
  fmt::print("frames: {} decoded ({} steady, scored against ground truth), period {:.3f} ms\n", s.frames,
             s.steady_frames, period * 1e3);
  const auto& dcal = c.dcal;
  if (h.wants(HallDecode::Decouple))
    fmt::print("decouple (seed 001): mean |error| shear {:.2f}% of {:.2f} N, normal {:.2f}% of {:.2f} N; "
               "{} frames out of range; k1 {} c1 {:.1f} uT, k2 {} c2 {:.1f} uT\n",
               100 * s.e_shear.get(), dcal.shear_fs_n, 100 * s.e_normal.get(), dcal.normal_fs_n, s.invalid,
               dcal.params.k1, dcal.params.c1_ut, dcal.params.k2, dcal.params.c2_ut);
  if (h.wants(HallDecode::Wrench)) {
    double avg = 0;
    const char* names[] = {"Fx", "Fy", "Fz", "Tx", "Ty", "Tz"};
    fmt::print("wrench (seed 002, C 6x9 from {} presses): mean |error| in % of calibration range:", c.wcal.presses);
    for (int a = 0; a < 6; ++a) fmt::print(" {} {:.2f}%", names[a], 100 * s.e_w[size_t(a)].get()), avg += s.e_w[size_t(a)].get() / 6;
    fmt::print("; average {:.2f}%\n", 100 * avg);
  }
  if (h.wants(HallDecode::ForceCurve)) {
    const char* names[] = {"range 1 (0..0.9 N)", "range 2 (0.9..4.8 N)", "range 3 (4.8..16.2 N)"};
    for (int r = 0; r < 3; ++r)
      fmt::print("force curve (seed 003) {}: {} frames, mean |error| {:.2f}% of the range's top, {:.2f}% of the force\n",
                 names[r], s.e_range[size_t(r)].n, 100 * s.e_range[size_t(r)].get(), 100 * s.e_range_rel[size_t(r)].get());
  }
  if (c.loc)
    fmt::print("locate (seed 000): single presses {:.2f} mm mean error ({} frames), force {:.1f}%; "
               "multi-point {:.2f} mm ({}); rolling ball {:.2f} mm ({})\n",
               s.e_loc1.get(), s.e_loc1.n, 100 * s.e_f1.get(), s.e_locm.get(), s.e_locm.n, s.e_roll.get(), s.e_roll.n);
}

}  // namespace

int run_hall_golden(const sim::HallWorld& w, double duration_s, uint64_t seed, const std::string& out_dir) {
  const HallConfig& h = w.config();
  namespace fs = std::filesystem;
  fs::create_directories(out_dir);
  auto nd = fmt::output_file((fs::path(out_dir) / "hall.ndjson").string());
  fmt::print("hall: {} sensors on {} bus(es), {} magnets, {} cells; {}\n", h.sensors.size(),
             h.bus_count(), h.magnets.size(), h.cells.size(), speed(h));
  HallGoldenCal c;
  calibrate_blocks(w, seed, c);
  sim::HallSampler sampler(h, seed);
  golden::HallBaseline base = capture_baseline(h, w.scene(), sampler);
  HallGoldenScores s;
  decode_frames(w, duration_s, sampler, base, c, nd, s);
  print_scores(h, c, s, sampler.period_s());
  fmt::print("hall outputs written to {}/hall.ndjson\n", out_dir);
  return 0;
}

}  // namespace eskin::hall
