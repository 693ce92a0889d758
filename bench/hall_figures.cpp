// Hall accuracy figures through the FPGA's fixed-point kernels (hls/),
// beside the golden chain's: each shipped seed scene is sampled (device
// law, noise), calibrated by the golden chain, then decoded by the HLS
// kernels exactly as the RTL does (bit-exact, tests/rtl) and scored on the
// steady frames against the world's truth.
//   build/bin/hall_figures [--osr N --dig-filt N]
// Prints one line per figure; the golden figures come from `eskin golden`.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "host/hall/hall_chain.h"
#include "hls/force_curve.h"
#include "hls/force_curve_config.h"
#include "hls/ft_calibrate.h"
#include "hls/ft_calibrate_config.h"
#include "hls/hall_baseline.h"
#include "hls/hall_decouple.h"
#include "host/golden/hall_decouple.h"
#include "sim/scene.h"

using namespace eskin;

namespace {

struct Mean {
  double sum = 0;
  int n = 0;
  void add(double v) { sum += v, ++n; }
  double get() const { return n ? sum / n : 0; }
};

sim::Scene scene(const char* name, int osr, int df) {
  sim::Scene s = sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/" + name);
  hall::apply_speed(s.hall.config, osr, df);
  return s;
}

// Device-quantised tokens of the scene, frame by frame, in the device's code format.
template <class F>
void for_each_frame(const sim::HallWorld& w, double duration, uint64_t seed, F f) {
  sim::HallSampler smp(w.config(), seed);
  for (double t = 0; t < duration; t += smp.period_s()) {
    std::vector<hls::HallSampleToken> toks;
    for (const HallSample& x : smp.sample(w, t)) {
      hls::HallSampleToken k;
      k.id = x.sensor, k.t = x.t_us, k.flags = x.flags;
      k.x = uint16_t(x.lsb[0]), k.y = uint16_t(x.lsb[1]), k.z = uint16_t(x.lsb[2]);  // RES 0: two's complement
      toks.push_back(k);
    }
    f(t, toks);
  }
}

void seed001(int osr, int df) {
  const sim::Scene s = scene("hall_001_split.yaml", osr, df);
  const sim::HallWorld w(s.hall);
  const HallConfig& h = w.config();
  const hall::DecoupleCalibration cal = hall::calibrate_decouple(w, s.seed);
  hls::HallDecoupleConfig c;
  for (int a = 0; a < 3; ++a) c.gain[a] = uint32_t(std::lround(mlx90393::sensitivity_uT(h.mlx, a) * 65536));
  c.k1 = int16_t(std::lround(cal.params.k1 * 16384)), c.k2 = int16_t(std::lround(cal.params.k2 * 16384));
  c.c1 = int32_t(std::lround(cal.params.c1_ut * 64)), c.c2 = int32_t(std::lround(cal.params.c2_ut * 64));
  hls::HallBaseline<1, 4> base;
  for (int a = 0; a < 3; ++a)
    base.set(0, a, int16_t(std::lround(h.geomagnetic_ut[size_t(a)] / mlx90393::sensitivity_uT(h.mlx, a))));
  hls::HallDecouple<0> k(c);
  const golden::Decoupled rest = golden::hall_decouple(cal.rest_film_ut, cal.params);
  Mean shear, normal;
  for_each_frame(w, s.duration_s, s.seed, [&](double t, const std::vector<hls::HallSampleToken>& toks) {
    hls::HallDeltaToken d;
    hls::DecoupleToken o;
    if (!base.push(toks[0], d) || !k.push(d, o) || !o.valid) return;
    bool steady;
    hall::active_stimuli(w.scene(), t, steady);
    if (!steady) return;
    golden::Decoupled g;
    g.rx = o.rx / 16777216.0, g.ry = o.ry / 16777216.0, g.sz = o.sz / 16777216.0, g.valid = true;
    const Vec3 f = golden::decoupled_force(g, rest, cal.params);
    const auto tr = w.truth(t);
    shear.add(std::fabs(f[0] - tr.force_n[0]) / cal.shear_fs_n);
    shear.add(std::fabs(f[1] - tr.force_n[1]) / cal.shear_fs_n);
    normal.add(std::fabs(f[2] + tr.force_n[2]) / cal.normal_fs_n);
  });
  std::printf("seed 001 (hls hall_decouple + host force polynomials), OSR %d DIG_FILT %d: shear %.2f%%, normal %.2f%% of full scale (%d frames)\n",
              h.mlx.osr, h.mlx.dig_filt, 100 * shear.get(), 100 * normal.get(), normal.n);
}

void seed002(int osr, int df) {
  const sim::Scene s = scene("hall_002_magtac.yaml", osr, df);
  const sim::HallWorld w(s.hall);
  const HallConfig& h = w.config();
  const hall::WrenchCalibration cal = hall::calibrate_wrench(w, s.seed);
  hls::FtCalibrate<16> k;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j)
      k.load(i, j, hls::ft_entry(cal.c(i, j), mlx90393::sensitivity_uT(h.mlx, j % 3), 16, i, j));
  hls::HallBaseline<3, 4> base;
  Mean e[6];
  for_each_frame(w, s.duration_s, s.seed, [&](double t, const std::vector<hls::HallSampleToken>& toks) {
    hls::WrenchToken o;
    bool out = false;
    for (const auto& x : toks) {
      hls::HallDeltaToken d;
      if (base.push(x, d)) out = k.push(d, o);
    }
    bool steady;
    hall::active_stimuli(w.scene(), t, steady);
    if (!out || !steady) return;
    const auto tr = w.truth(t);
    const double truth[6] = {tr.force_n[0], tr.force_n[1], tr.force_n[2], tr.torque_nmm[0], tr.torque_nmm[1], tr.torque_nmm[2]};
    for (int a = 0; a < 6; ++a) e[a].add(std::fabs(o.w[a] / 1000.0 - truth[a]) / cal.full_scale(a));
  });
  double avg = 0;
  for (auto& m : e) avg += m.get() / 6;
  std::printf("seed 002 (hls ft_calibrate), OSR %d DIG_FILT %d: Fx %.2f Fy %.2f Fz %.2f Tx %.2f Ty %.2f Tz %.2f %% of range, average %.2f%% (%d frames)\n",
              h.mlx.osr, h.mlx.dig_filt, 100 * e[0].get(), 100 * e[1].get(), 100 * e[2].get(), 100 * e[3].get(),
              100 * e[4].get(), 100 * e[5].get(), 100 * avg, e[0].n);
}

void seed003(int osr, int df) {
  const sim::Scene s = scene("hall_003_metamaterial.yaml", osr, df);
  const sim::HallWorld w(s.hall);
  const HallConfig& h = w.config();
  const auto curves = hall::calibrate_force_curves(w, s.seed);
  constexpr int kNb = 13;
  hls::ForceCurveConfig<kNb, 3> cfg;
  for (int a = 0; a < 3; ++a) cfg.gain[a] = hls::force_curve_gain(mlx90393::sensitivity_uT(h.mlx, a));
  const auto lock = h.cells[0].stack_lock_forces_n();
  for (int r = 0; r < 3; ++r) cfg.lock_mn[r] = int32_t(std::lround(lock[size_t(r)] * 1000));
  hls::ForceCurve<9, kNb> k(cfg);
  for (int c = 0; c < 9; ++c)
    k.table(c) = hls::force_curve_table<kNb>(curves[size_t(c)].db_ut.data(), curves[size_t(c)].force_n.data(), kNb);
  hls::HallBaseline<9, 4> base;
  Mean top[3], rel[3];
  for_each_frame(w, s.duration_s, s.seed, [&](double t, const std::vector<hls::HallSampleToken>& toks) {
    bool steady;
    hall::active_stimuli(w.scene(), t, steady);
    const auto tr = w.truth(t);
    for (const auto& x : toks) {
      hls::HallDeltaToken d;
      hls::ForceToken o;
      if (!base.push(x, d) || !k.push(d, o) || !steady) continue;
      const double ft = -tr.cells[o.cell].force_n[2];
      if (ft <= 0) continue;
      const size_t r = size_t(std::lower_bound(lock.begin(), lock.end(), ft) - lock.begin());
      if (r > 2) continue;
      top[r].add(std::fabs(o.force_mn / 1000.0 - ft) / lock[r]);
      rel[r].add(std::fabs(o.force_mn / 1000.0 - ft) / ft);
    }
  });
  for (int r = 0; r < 3; ++r)
    std::printf("seed 003 (hls force_curve) range %d (to %.1f N), OSR %d DIG_FILT %d: %.2f%% of the range's top, %.2f%% of the force (%d frames)\n",
                r + 1, lock[size_t(r)], h.mlx.osr, h.mlx.dig_filt, 100 * top[r].get(), 100 * rel[r].get(), top[r].n);
}

}  // namespace

int main(int argc, char** argv) {
  int osr = -1, df = -1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--osr")) osr = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--dig-filt")) df = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: hall_figures [--osr N] [--dig-filt N]\n");
      return 2;
    }
  }
  seed001(osr, df);
  seed002(osr, df);
  seed003(osr, df);
  return 0;
}
