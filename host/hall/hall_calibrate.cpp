#include "host/hall/hall_calibrate.h"

#include <fmt/format.h>
#include <fmt/os.h>
#include <fmt/ranges.h>

#include "host/hall/hall_chain.h"

namespace eskin::hall {
namespace {

std::string yaml_list(const std::vector<double>& v) { return fmt::format("[{:.9g}]", fmt::join(v, ", ")); }

}  // namespace

int run_hall_calibrate(const sim::Scene& scene, const std::string& scene_file,
                       const HallCalibrateOptions& a) {
  const sim::HallWorld w(scene.hall);
  const HallConfig& h = w.config();
  std::string yaml = fmt::format("# eskin calibrate {}\n", scene_file);
  bool any = false;
  if (h.wants(HallDecode::Wrench)) {
    any = true;
    if (!a.write_presses.empty()) {
      // Simulated presses as a recording, in the --from format.
      auto out = fmt::output_file(a.write_presses);
      out.print("b1x,b1y,b1z,b2x,b2y,b2z,b3x,b3y,b3z,fx,fy,fz,tx,ty,tz\n");
      const WrenchPresses p = simulate_wrench_presses(w, scene.seed, a.presses);
      for (size_t k = 0; k < p.db_ut.size(); ++k)
        out.print("{:.6f},{:.6f}\n", fmt::join(p.db_ut[k].data(), p.db_ut[k].data() + 9, ","),
                  fmt::join(p.wrench[k].data(), p.wrench[k].data() + 6, ","));
      fmt::print("wrote {} simulated presses to {}\n", a.presses, a.write_presses);
    }
    const WrenchCalibration cal = a.from.empty() ? calibrate_wrench(w, scene.seed, a.presses)
                                                 : calibrate_wrench_csv(a.from);
    fmt::print("wrench: C (6x9, N and N*mm per uT) from {} {} presses\n", cal.presses,
               a.from.empty() ? "simulated" : "recorded");
    std::vector<double> flat;
    for (int i = 0; i < 6; ++i) {
      std::vector<double> row;
      for (int j = 0; j < 9; ++j) row.push_back(cal.c(i, j)), flat.push_back(cal.c(i, j));
      fmt::print("  [{:+.6e}]\n", fmt::join(row, ", "));
    }
    yaml += "wrench_matrix: " + yaml_list(flat) + "\n";
  } else if (!a.from.empty()) {
    throw ConfigError("--from", "expected recorded presses only for a wrench (seed 002) scene, got " + scene_file);
  }
  if (h.wants(HallDecode::Decouple)) {
    any = true;
    const DecoupleCalibration cal = calibrate_decouple(w, scene.seed);
    const DecoupleParams& p = cal.params;
    fmt::print("decouple: k1 {} c1 {:.2f} uT, k2 {} c2 {:.2f} uT; Fx(dRx) {}, Fy(dRy) {}, Fn(dSz) {}\n", p.k1,
               p.c1_ut, p.k2, p.c2_ut, yaml_list(p.poly[0]), yaml_list(p.poly[1]), yaml_list(p.poly[2]));
    yaml += fmt::format("decouple: {{k1: {}, c1_ut: {:.9g}, k2: {}, c2_ut: {:.9g}, fx: {}, fy: {}, fn: {}}}\n", p.k1,
                        p.c1_ut, p.k2, p.c2_ut, yaml_list(p.poly[0]), yaml_list(p.poly[1]), yaml_list(p.poly[2]));
  }
  if (h.wants(HallDecode::ForceCurve)) {
    any = true;
    const auto curves = calibrate_force_curves(w, scene.seed);
    yaml += "force_curves:\n";
    for (size_t c = 0; c < curves.size(); ++c) {
      fmt::print("force curve {}: dB {} uT -> F {} N\n", c, yaml_list(curves[c].db_ut), yaml_list(curves[c].force_n));
      yaml += fmt::format("  - {{db_ut: {}, force_n: {}}}\n", yaml_list(curves[c].db_ut), yaml_list(curves[c].force_n));
    }
  }
  if (!any)
    throw ConfigError("hall.decode", "expected wrench, decouple or force_curve to calibrate (locate: use eskin locate), got none");
  if (!a.out.empty()) {
    auto out = fmt::output_file(a.out);
    out.print("{}", yaml);
    fmt::print("calibration written to {}\n", a.out);
  }
  return 0;
}

}  // namespace eskin::hall
