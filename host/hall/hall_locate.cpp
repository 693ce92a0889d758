#include "host/hall/hall_locate.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <cmath>
#include <filesystem>

#include "host/golden/hall_baseline.h"
#include "host/hall/hall_chain.h"

namespace eskin::hall {

int run_hall_locate(const sim::Scene& scene, const HallLocateOptions& a) {
  const sim::HallWorld w(scene.hall);
  const HallConfig& h = w.config();
  const golden::ContactLocator loc = calibrate_locator(w, scene.seed);
  namespace fs = std::filesystem;
  fs::create_directories(a.out);
  fmt::print("table: {}x{} entries at {:.2f} mm from a {} mm scan at {} N\n", loc.table_nx(), loc.table_ny(),
             loc.table_pitch_mm(), h.scan_pitch_mm, h.scan_normal_n);
  if (a.table) {
    auto t = fmt::output_file((fs::path(a.out) / "table.csv").string());
    for (int j = 0; j < loc.table_ny(); ++j)
      for (int i = 0; i < loc.table_nx(); ++i) {
        const auto p = loc.position(i, j);
        const auto& e = loc.entry(i, j);
        t.print("{:.3f},{:.3f},{:.4f}\n", p[0], p[1], fmt::join(e.data(), e.data() + e.size(), ","));
      }
  }
  auto out = fmt::output_file((fs::path(a.out) / "contacts.csv").string());
  out.print("t_s,contact,x_mm,y_mm,force_n,truth_x_mm,truth_y_mm,truth_force_n\n");
  sim::HallSampler sampler(h, scene.seed);
  golden::HallBaseline base(h.sensors.size(), 1);
  std::vector<Vec3> d;
  double err = 0;
  int n = 0;
  const size_t frames = size_t(scene.duration_s / sampler.period_s());
  for (size_t k = 0; k < frames; ++k) {
    const double t = double(k) * sampler.period_s();
    if (!base.push(golden::frame_ut(sampler.sample(w, t), h.mlx), d)) continue;
    Eigen::VectorXd x(Eigen::Index(3 * d.size()));
    for (size_t s = 0; s < d.size(); ++s)
      for (size_t c = 0; c < 3; ++c) x(Eigen::Index(3 * s + c)) = d[s][c];
    const sim::HallTruth truth = w.truth(t);
    if (truth.contacts.empty()) continue;
    const auto found = loc.locate(x, a.max_contacts);
    for (size_t i = 0; i < found.size(); ++i) {
      // The true contact nearest to this one.
      const sim::ContactLoad* best = &truth.contacts[0];
      for (const auto& c : truth.contacts)
        if (std::hypot(c.point_mm[0] - found[i].x_mm, c.point_mm[1] - found[i].y_mm) <
            std::hypot(best->point_mm[0] - found[i].x_mm, best->point_mm[1] - found[i].y_mm))
          best = &c;
      const double e = std::hypot(best->point_mm[0] - found[i].x_mm, best->point_mm[1] - found[i].y_mm);
      if (truth.contacts.size() == 1 && i == 0) err += e, ++n;
      out.print("{:.6f},{},{:.2f},{:.2f},{:.3f},{:.2f},{:.2f},{:.3f}\n", t, i, found[i].x_mm, found[i].y_mm,
                found[i].force_n, best->point_mm[0], best->point_mm[1], -best->force_n[2]);
    }
  }
  fmt::print("single-contact frames: {} (ramps included), mean error {:.2f} mm; contacts written to {}/contacts.csv\n",
             n, n ? err / n : 0.0, a.out);
  return 0;
}

}  // namespace eskin::hall
