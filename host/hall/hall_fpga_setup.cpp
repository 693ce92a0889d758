#include "host/hall/hall_fpga_setup.h"

#include <cmath>
#include <string>

#include "eskin/mlx90393_config.h"
#include "hls/force_curve_config.h"
#include "hls/ft_calibrate_config.h"
#include "host/link/hall_packets.h"

namespace eskin::hall {
namespace {

constexpr int kFtFrac = 16;  // rtl/hall_top.v's ft_calibrate C_FRAC
constexpr int kCurveNb = 3 * sim::HallTopSpec::kCurvePerRange + 1;  // three ranges (CURVE_NR)

// Scene sensor i must sit in FPGA slot first + i for i < n.
void expect_slots(const sim::HallTopSpec& spec, int first, size_t n, const char* what) {
  for (size_t i = 0; i < n; ++i)
    if (i >= spec.slot.size() || spec.slot[i] != first + int(i))
      throw ConfigError("hall.sensors", std::string(what) + " expects scene sensor " +
                                            std::to_string(i) + " in FPGA slot " +
                                            std::to_string(first + int(i)));
}

}  // namespace

HallFpgaSetup hall_fpga_setup(const sim::HallWorld& w, const sim::HallTopSpec& spec,
                              uint64_t seed, link::LinkEncoder& enc) {
  const HallConfig& h = w.config();
  HallFpgaSetup s;
  auto add = [&](const std::vector<uint8_t>& f) {
    s.commands.insert(s.commands.end(), f.begin(), f.end());
    ++s.command_count;
  };
  if (spec.decouple) {
    expect_slots(spec, spec.dec_id, 1, "decouple");
    s.decouple = calibrate_decouple(w, seed);
    for (int a = 0; a < 3; ++a)
      add(link::hall_set_baseline(
          enc, uint8_t(spec.dec_id), uint8_t(a),
          int16_t(std::lround(h.geomagnetic_ut[size_t(a)] / mlx90393::sensitivity_uT(h.mlx, a)))));
    const auto& p = s.decouple.params;  // Q2.14 slopes, 1/64 uT offsets (hls/hall_decouple.h)
    add(link::hall_set_decouple(enc, int16_t(std::lround(p.k1 * 16384)), int32_t(std::lround(p.c1_ut * 64)),
                                int16_t(std::lround(p.k2 * 16384)), int32_t(std::lround(p.c2_ut * 64))));
  }
  if (spec.ft) {
    expect_slots(spec, spec.ft_id, 3, "wrench");
    s.wrench = calibrate_wrench(w, seed);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 9; ++j)
        add(link::hall_load_c(enc, uint8_t(i), uint8_t(j),
                              hls::ft_entry(s.wrench.c(i, j), mlx90393::sensitivity_uT(h.mlx, j % 3),
                                            kFtFrac, i, j)));
  }
  if (spec.curve) {
    expect_slots(spec, spec.curve_id, size_t(spec.nc), "force_curve");
    if (spec.curve_nb != kCurveNb)
      throw ConfigError("hall.decode", "force_curve: expected " + std::to_string(kCurveNb) +
                                           " breakpoints per cell, the build has " +
                                           std::to_string(spec.curve_nb));
    s.curves = calibrate_force_curves(w, seed);
    for (int c = 0; c < spec.nc; ++c) {
      const auto& cv = s.curves[size_t(c)];
      const auto t = hls::force_curve_table<kCurveNb>(cv.db_ut.data(), cv.force_n.data(), int(cv.db_ut.size()));
      for (int i = 0; i < kCurveNb; ++i)
        for (int which = 0; which < 3; ++which)
          add(link::hall_load_curve(enc, uint8_t(c), uint8_t(i), uint8_t(which),
                                    which == 0 ? t.db[i] : which == 1 ? t.f[i] : t.slope[i]));
    }
  }
  return s;
}

}  // namespace eskin::hall
