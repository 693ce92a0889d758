#include "cli/simulate_hall.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <thread>

#include "cli/board_link.h"
#include "cli/command.h"
#include "cli/hall_fpga_setup.h"
#include "cli/progress.h"
#include "eskin/mlx90393_config.h"
#include "host/golden/contact_locate.h"
#include "host/golden/force_curve.h"
#include "host/golden/hall_baseline.h"
#include "host/link/hall_packets.h"
#include "host/link/link_decoder.h"
#include "host/report/html_page.h"
#include "host/stream/link_stream.h"
#include "host/stream/packet_table.h"
#include "sim/vboard/hall_build.h"
#include "sim/vboard/vboard_build.h"
#include "sim/vboard/vboard_process.h"

namespace eskin::cli {
namespace {

namespace fs = std::filesystem;
using link::Packet;

// hall_baseline's capture on the FPGA: the first 2^4 data readings of each
// sensor (rtl/hall_top.v); the golden side captures as many frames.
constexpr int kCaptureFrames = 16;

// One HALL_SAMPLES frame and the decoding packets that follow it.
struct HallFrameRx {
  const Packet* samples = nullptr;
  double arrival_us = -1, last_arrival_us = -1;  // its last byte / its last packet's
  const Packet* decouple = nullptr;
  const Packet* wrench = nullptr;
  const Packet* forces = nullptr;
  double drdy_us = -1;  // the newest DRDY among its readings
};

struct Mean {
  double sum = 0;
  int n = 0;
  void add(double v) { sum += v, ++n; }
  double get() const { return n ? sum / n : 0; }
};

const char* kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                          "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

// A time series of the report: FPGA solid, golden dashed, truth dotted.
struct Series {
  std::string label;
  int colour = 0, style = 0;  // 0 FPGA, 1 golden, 2 truth
  std::vector<double> t, v;
  void add(double ts, double val) { t.push_back(ts), v.push_back(val); }
};

void series_chart(report::Page& page, const std::vector<Series>& ss, const std::string& y) {
  nlohmann::json sets = nlohmann::json::array();
  for (const Series& s : ss) {
    nlohmann::json pts = nlohmann::json::array();
    for (size_t i = 0; i < s.t.size(); ++i) pts.push_back({{"x", s.t[i]}, {"y", s.v[i]}});
    nlohmann::json d = {{"label", s.label}, {"data", pts}, {"borderColor", kColours[s.colour % 10]},
                        {"pointRadius", 0}, {"borderWidth", s.style == 0 ? 1.5 : 1}};
    if (s.style == 1) d["borderDash"] = {5, 3};
    if (s.style == 2) d["borderDash"] = {1, 2};
    sets.push_back(d);
  }
  page.chart({{"type", "line"},
              {"data", {{"datasets", sets}}},
              {"options",
               {{"parsing", false},
                {"scales",
                 {{"x", {{"type", "linear"}, {"title", {{"display", true}, {"text", "time (s)"}}}}},
                  {"y", {{"title", {{"display", true}, {"text", y}}}}}}}}}},
             340);
}

std::string pct(double v) { return fmt::format("{:.2f} %", 100 * v); }

}  // namespace

HallFpgaSetup hall_simulation_setup(const sim::Scene& scene, const sim::HallTopSpec& spec) {
  const sim::HallWorld world(scene.hall);
  link::LinkEncoder enc;
  return hall_fpga_setup(world, spec, scene.seed, enc);
}

nlohmann::json report_hall(const sim::Scene& scene, const std::string& scene_file,
                           const vboard::HallBuild& build, const HallFpgaSetup& setup,
                           const BoardRun& run, const std::string& out_dir) {
  fs::create_directories(out_dir);
  const sim::HallWorld world(scene.hall);
  const HallConfig& h = world.config();
  const sim::HallTopSpec& spec = build.spec;
  const nlohmann::json& done = run.done;
  const link::DecoderStats& ls = run.link;
  const uint64_t link_errors = ls.crc_errors + ls.framing_errors + ls.payload_errors;
  std::vector<Packet> rx;  // the Hall top's packets, with their arrivals
  std::vector<double> arrival;
  for (size_t i = 0; i < run.rx.size(); ++i)
    if (link::is_hall_packet(run.rx[i].type)) {
      rx.push_back(run.rx[i]);
      arrival.push_back(run.arrival_us[i]);
    }
  // ---- frames: HALL_SAMPLES and the decoding packets after it.
  std::vector<HallFrameRx> frames;
  const Packet* bus_status = nullptr;
  const Packet* decode_status = nullptr;
  const auto& drdy = done.at("drdy_ns");
  std::vector<size_t> read_k(spec.nb * spec.nsb, 0);  // data readings per slot so far
  auto nd = fmt::output_file((fs::path(out_dir) / "fpga_packets.ndjson").string());
  for (size_t i = 0; i < rx.size(); ++i) {
    const Packet& p = rx[i];
    const double arr = arrival[i];
    // The packet as `eskin stream` writes it (host/stream/packet_table.h:
    // one row per reading, record or packet), with its arrival.
    if (const stream::PacketKind* kind = stream::find_kind(p.type)) {
      std::vector<stream::Row> rows;
      kind->rows(p, rows);
      for (const stream::Row& r : rows)
        nd.print("{{\"arrival_us\":{:.2f},{}\n", arr, stream::ndjson_line(*kind, r).substr(1));
    }
    if (p.type == link::kHallSamples) {
      HallFrameRx f;
      f.samples = &p;
      f.arrival_us = f.last_arrival_us = arr;
      for (size_t s = 0; s < p.hall_samples.size() && s < read_k.size(); ++s) {
        if (!p.hall_samples[s].has_data()) continue;
        const size_t k = read_k[s]++;
        if (k < drdy[s].size()) f.drdy_us = std::max(f.drdy_us, drdy[s][k].get<double>() / 1000.0);
      }
      frames.push_back(f);
      continue;
    }
    if (p.type == link::kHallBusStatus) bus_status = &p;
    if (p.type == link::kHallDecodeStatus) decode_status = &p;
    if (frames.empty()) continue;
    HallFrameRx& f = frames.back();
    if (p.type == link::kHallDecouple3) f.decouple = &p;
    else if (p.type == link::kHallWrench6) f.wrench = &p;
    else if (p.type == link::kHallForceCurve) f.forces = &p;
    else if (p.type != link::kHallDeltas) continue;
    f.last_arrival_us = arr;
  }

  // ---- the golden chain on the FPGA's own readings, both against the truth.
  const size_t ns = h.sensors.size();
  golden::HallBaseline base(ns, kCaptureFrames);
  if (spec.decouple) base.set(std::vector<Vec3>(ns, h.geomagnetic_ut));  // as the commands set it
  const auto& dcal = setup.decouple;
  const golden::Decoupled rest = golden::hall_decouple(dcal.rest_film_ut, dcal.params);
  // Seed 000: localisation is host-side by design (docs/hall_fpga.md): the
  // golden locator on the FPGA's readings.
  std::unique_ptr<golden::ContactLocator> loc;
  if (h.wants(HallDecode::Locate))
    loc = std::make_unique<golden::ContactLocator>(calibrate_locator(world, scene.seed));
  Mean loc1, locm, locroll;
  Mean f_shear, f_normal, g_shear, g_normal;
  std::array<Mean, 6> f_w, g_w;
  std::array<Mean, 3> f_range, g_range;
  std::vector<double> latencies;
  std::vector<Series> force_s, field_s;
  const char* axis[] = {"Fx", "Fy", "Fz", "Tx", "Ty", "Tz"};
  for (int a = 0; a < 3 && (spec.decouple || spec.ft); ++a)
    for (int m = 0; m < 3; ++m)
      force_s.push_back({fmt::format("{} {}", m == 0 ? "FPGA" : m == 1 ? "golden" : "truth", axis[a]), a, m, {}, {}});
  std::vector<Series> torque_s, cell_s;
  for (int a = 3; a < 6 && spec.ft; ++a)
    for (int m = 0; m < 3; ++m)
      torque_s.push_back({fmt::format("{} {}", m == 0 ? "FPGA" : m == 1 ? "golden" : "truth", axis[a]), a, m, {}, {}});
  for (int c = 0; c < spec.nc && spec.curve; ++c)
    for (int m = 0; m < 3; m += 2)
      cell_s.push_back({fmt::format("{} cell {}", m == 0 ? "FPGA" : "truth", c), c, m, {}, {}});
  for (size_t s = 0; s < ns && s < 10; ++s) field_s.push_back({fmt::format("sensor {} |B - baseline|", s), int(s), 0, {}, {}});
  size_t incomplete = 0, scored = 0;
  auto csv = fmt::output_file((fs::path(out_dir) / "hall_frames.csv").string());
  {
    std::string head = "t_s,arrival_us,drdy_to_host_us,steady";
    auto cols = [&](const std::vector<std::string>& names) {
      for (const char* m : {"fpga", "golden", "truth"})
        for (const auto& n : names) head += fmt::format(",{}_{}", m, n);
    };
    if (spec.decouple) cols({"fx_n", "fy_n", "fnormal_n"});
    if (spec.ft) cols({"fx_n", "fy_n", "fz_n", "tx_nmm", "ty_nmm", "tz_nmm"});
    if (h.wants(HallDecode::Locate)) head += ",golden_contacts_x_y_n";
    if (spec.curve) {
      std::vector<std::string> cells;
      for (int c = 0; c < spec.nc; ++c) cells.push_back(fmt::format("cell{}_n", c));
      cols(cells);
    }
    csv.print("{}\n", head);
  }
  std::vector<Vec3> delta;
  for (const HallFrameRx& f : frames) {
    const Packet& p = *f.samples;
    const double t = p.t * 1e-6;
    if (f.drdy_us >= 0 && f.last_arrival_us >= 0) {
      latencies.push_back(f.last_arrival_us - f.drdy_us);
    }
    std::vector<Vec3> ut(ns);
    bool complete = p.hall_samples.size() == size_t(spec.nb * spec.nsb);
    for (size_t i = 0; i < ns && complete; ++i) {
      const link::HallSample& hs = p.hall_samples[size_t(spec.slot[i])];
      complete = hs.has_data();
      const uint16_t code[3] = {hs.x, hs.y, hs.z};
      for (int a = 0; a < 3; ++a) ut[i][size_t(a)] = mlx90393::decode_uT(h.mlx, a, code[a]);
    }
    if (!complete) {
      ++incomplete;
      continue;
    }
    if (!base.push(ut, delta)) continue;
    bool steady = false;
    const int active = active_stimuli(scene.hall, t, steady);
    const sim::HallTruth truth = world.truth(t);
    for (size_t s = 0; s < field_s.size(); ++s)
      field_s[s].add(t, std::sqrt(delta[s][0] * delta[s][0] + delta[s][1] * delta[s][1] + delta[s][2] * delta[s][2]));
    scored += steady;
    std::string line = fmt::format("{:.6f},{:.2f},{:.2f},{}", t, f.arrival_us,
                                   f.drdy_us >= 0 && f.last_arrival_us >= 0 ? f.last_arrival_us - f.drdy_us : -1.0,
                                   steady ? 1 : 0);
    if (spec.decouple) {
      const Vec3 ft{truth.force_n[0], truth.force_n[1], -truth.force_n[2]};
      const golden::Decoupled gd = golden::hall_decouple(delta[0], dcal.params);
      const Vec3 gf = gd.valid ? golden::decoupled_force(gd, rest, dcal.params) : Vec3{0, 0, 0};
      Vec3 ff{0, 0, 0};
      bool fvalid = false;
      if (f.decouple && f.decouple->hall.decouple.valid) {
        golden::Decoupled d;
        d.rx = f.decouple->hall.decouple.rx / 16777216.0;  // Q8.24
        d.ry = f.decouple->hall.decouple.ry / 16777216.0;
        d.sz = f.decouple->hall.decouple.sz / 16777216.0;
        d.valid = fvalid = true;
        ff = golden::decoupled_force(d, rest, dcal.params);
      }
      for (int a = 0; a < 3; ++a) {
        if (fvalid) force_s[size_t(3 * a)].add(t, ff[size_t(a)]);
        force_s[size_t(3 * a + 1)].add(t, gf[size_t(a)]);
        force_s[size_t(3 * a + 2)].add(t, ft[size_t(a)]);
      }
      if (steady && fvalid) {
        f_shear.add(std::fabs(ff[0] - ft[0]) / dcal.shear_fs_n);
        f_shear.add(std::fabs(ff[1] - ft[1]) / dcal.shear_fs_n);
        f_normal.add(std::fabs(ff[2] - ft[2]) / dcal.normal_fs_n);
      }
      if (steady && gd.valid) {
        g_shear.add(std::fabs(gf[0] - ft[0]) / dcal.shear_fs_n);
        g_shear.add(std::fabs(gf[1] - ft[1]) / dcal.shear_fs_n);
        g_normal.add(std::fabs(gf[2] - ft[2]) / dcal.normal_fs_n);
      }
      line += fmt::format(",{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}", ff[0],
                          ff[1], ff[2], gf[0], gf[1], gf[2], ft[0], ft[1], ft[2]);
    }
    if (spec.ft) {
      std::string fs_, gs_, ts_;
      golden::Vec9 b;
      for (int i = 0; i < 9; ++i) b(i) = delta[size_t(i / 3)][size_t(i % 3)];
      const golden::Vec6 gw = golden::ft_apply(setup.wrench.c, b);
      golden::Vec6 tw;
      tw << truth.force_n[0], truth.force_n[1], truth.force_n[2], truth.torque_nmm[0],
          truth.torque_nmm[1], truth.torque_nmm[2];
      for (int a = 0; a < 6; ++a) {
        auto& ser = a < 3 ? force_s : torque_s;
        const size_t k = size_t(3 * (a % 3));
        const double fw = f.wrench ? f.wrench->hall.wrench.w[a] / 1000.0 : 0;  // mN, mN*mm
        if (f.wrench) ser[k].add(t, fw);
        ser[k + 1].add(t, gw(a));
        ser[k + 2].add(t, tw(a));
        fs_ += fmt::format(",{:.4f}", f.wrench ? fw : std::nan(""));
        gs_ += fmt::format(",{:.4f}", gw(a));
        ts_ += fmt::format(",{:.4f}", tw(a));
        if (!steady) continue;
        if (f.wrench) f_w[size_t(a)].add(std::fabs(fw - tw(a)) / setup.wrench.full_scale(a));
        g_w[size_t(a)].add(std::fabs(gw(a) - tw(a)) / setup.wrench.full_scale(a));
      }
      line += fs_ + gs_ + ts_;
    }
    if (spec.curve) {
      std::string fs_, gs_, ts_;
      size_t ci = 0;
      for (size_t i = 0; i < h.cells.size(); ++i) {
        if (h.cells[i].kind != CellKind::Stack) continue;
        const size_t c = ci++;
        const double gf = golden::force_curve_apply(setup.curves[c], std::sqrt(
            delta[i][0] * delta[i][0] + delta[i][1] * delta[i][1] + delta[i][2] * delta[i][2]));
        const double tf = -truth.cells[i].force_n[2];
        double ff = -1;
        if (f.forces)
          for (const auto& r : f.forces->hall.forces)
            if (r.cell == c && !(r.flags & link::HallSample::kReply)) ff = r.force_mn / 1000.0;
        if (c < size_t(spec.nc)) {
          if (ff >= 0) cell_s[2 * c].add(t, ff);
          cell_s[2 * c + 1].add(t, tf);
          fs_ += fmt::format(",{:.4f}", ff >= 0 ? ff : std::nan(""));
          gs_ += fmt::format(",{:.4f}", gf);
          ts_ += fmt::format(",{:.4f}", tf);
        }
        if (!steady || tf <= 0) continue;
        const auto lock = h.cells[i].stack_lock_forces_n();
        const size_t r = size_t(std::lower_bound(lock.begin(), lock.end(), tf) - lock.begin());
        if (r >= 3) continue;
        if (ff >= 0) f_range[r].add(std::fabs(ff - tf) / lock[r]);
        g_range[r].add(std::fabs(gf - tf) / lock[r]);
      }
      line += fs_ + gs_ + ts_;
    }
    if (loc) {
      Eigen::VectorXd x(Eigen::Index(3 * ns));
      for (size_t i = 0; i < ns; ++i)
        for (size_t a = 0; a < 3; ++a) x(Eigen::Index(3 * i + a)) = delta[i][a];
      const auto found = loc->locate(x, std::max(1, active), 0.05);
      std::string fx;
      for (const auto& g : found) fx += fmt::format("{}{:.2f};{:.2f};{:.3f}", fx.empty() ? "" : "|", g.x_mm, g.y_mm, g.force_n);
      line += "," + fx;
      const bool rolling = !scene.hall.rolls.empty() && scene.hall.rolls[0].envelope(t) > 0;
      for (const auto& c : truth.contacts) {  // each true contact against the nearest found one
        if (!steady) break;
        double best = 1e300;
        for (const auto& g : found) best = std::min(best, std::hypot(g.x_mm - c.point_mm[0], g.y_mm - c.point_mm[1]));
        (rolling ? locroll : truth.contacts.size() == 1 ? loc1 : locm).add(best);
      }
    }
    csv.print("{}\n", line);
  }

  // ---- report.
  report::Page page("eskin simulate: " + scene.name);
  const double sim_s = done.at("sim_s"), cpu_s = done.at("cpu_s"), wall_s = done.at("wall_s");
  const double cyc = done.at("cycles");
  std::sort(latencies.begin(), latencies.end());
  const double lat_med = latencies.empty() ? -1 : latencies[latencies.size() / 2];
  const double lat_max = latencies.empty() ? -1 : latencies.back();
  page.text(fmt::format(
      "Hall skin: {} MLX90393 on {} I2C bus(es) of {} (rtl/hall_top.v build {} at {:.0f} MHz, "
      "400 kHz I2C, UART {:.0f} baud); {:.3f} s of the scene. The decoding's constants were "
      "calibrated by the golden chain and sent over the link ({} commands); the golden chain "
      "decoded the FPGA's own readings. Scene file: {}.",
      ns, spec.nb, spec.nsb, build.key, build.clk_hz / 1e6, double(build.baud), sim_s,
      setup.command_count, scene_file));
  page.heading("Errors against the scene's truth (steady frames: every active stimulus at full force)");
  std::vector<std::string> head{"model"};
  std::vector<std::string> frow{"FPGA (virtual board)"}, grow{"golden (on the FPGA's readings)"};
  if (spec.decouple) {
    head.insert(head.end(), {fmt::format("shear, mean |error| of {:.2f} N", dcal.shear_fs_n),
                             fmt::format("normal, of {:.2f} N", dcal.normal_fs_n)});
    frow.insert(frow.end(), {pct(f_shear.get()), pct(f_normal.get())});
    grow.insert(grow.end(), {pct(g_shear.get()), pct(g_normal.get())});
  }
  if (spec.ft) {
    double fa = 0, ga = 0;
    for (int a = 0; a < 6; ++a) {
      head.push_back(fmt::format("{} (of its range)", axis[a]));
      frow.push_back(pct(f_w[size_t(a)].get()));
      grow.push_back(pct(g_w[size_t(a)].get()));
      fa += f_w[size_t(a)].get() / 6, ga += g_w[size_t(a)].get() / 6;
    }
    head.push_back("six-axis average");
    frow.push_back(pct(fa));
    grow.push_back(pct(ga));
  }
  if (spec.curve)
    for (int r = 0; r < 3; ++r) {
      head.push_back(fmt::format("force, range {} (of its top)", r + 1));
      frow.push_back(fmt::format("{} ({} frames)", pct(f_range[size_t(r)].get()), f_range[size_t(r)].n));
      grow.push_back(pct(g_range[size_t(r)].get()));
    }
  if (loc) {
    head.insert(head.end(), {"single press, position", "multi-point", "rolling ball"});
    frow.insert(frow.end(), {"host-side by design", "", ""});
    grow.insert(grow.end(), {fmt::format("{:.2f} mm ({} frames)", loc1.get(), loc1.n),
                             fmt::format("{:.2f} mm ({})", locm.get(), locm.n),
                             fmt::format("{:.2f} mm ({})", locroll.get(), locroll.n)});
  }
  head.push_back("frames scored");
  frow.push_back(std::to_string(scored));
  grow.push_back(std::to_string(scored));
  page.table(head, {frow, grow});
  if (!force_s.empty()) {
    page.heading("Force over time (FPGA solid, golden dashed, truth dotted)");
    series_chart(page, force_s, "force (N)");
  }
  if (!torque_s.empty()) series_chart(page, torque_s, "torque (N mm)");
  if (!cell_s.empty()) {
    page.heading("Cell forces (FPGA solid, truth dotted)");
    series_chart(page, cell_s, "force (N)");
  }
  page.heading("Field change at the sensors (baseline removed, from the FPGA's readings)");
  series_chart(page, field_s, "|B - baseline| (uT)");
  page.heading("Latency: a frame's newest DRDY to its last packet's last byte at the host");
  {
    const double bin = 50;
    std::vector<int> counts;
    for (double l : latencies) {
      const size_t b = size_t(std::max(0.0, l) / bin);
      if (counts.size() <= b) counts.resize(b + 1, 0);
      ++counts[b];
    }
    nlohmann::json labels = nlohmann::json::array(), vals = nlohmann::json::array();
    for (size_t b = 0; b < counts.size(); ++b) {
      labels.push_back(fmt::format("{:.0f}", b * bin));
      vals.push_back(counts[b]);
    }
    page.chart({{"type", "bar"},
                {"data", {{"labels", labels}, {"datasets", {{{"label", "frames"}, {"data", vals}, {"backgroundColor", kColours[0]}}}}}},
                {"options", {{"scales", {{"x", {{"title", {{"display", true}, {"text", "latency (us), 50 us bins"}}}}}}}}}});
  }
  page.heading("Run");
  std::vector<std::vector<std::string>> run_rows{
      {"FPGA build", build.key},
      {"simulated time (s)", fmt::format("{:.4f}", sim_s)},
      {"FPGA cycles", fmt::format("{:.0f}", cyc)},
      {"speed: simulated s per CPU s (board process)", fmt::format("{:.3f}", sim_s / cpu_s)},
      {"speed: simulated s per wall s", fmt::format("{:.3f}", sim_s / wall_s)},
      {"speed: FPGA cycles per CPU s", fmt::format("{:.3g}", cyc / cpu_s)},
      {"frames (HALL_SAMPLES) / incomplete", fmt::format("{} / {}", frames.size(), incomplete)},
      {"packets received", std::to_string(rx.size())},
      {"link: bytes / CRC errors / framing errors / lost packets",
       fmt::format("{} / {} / {} / {}", ls.bytes, ls.crc_errors, ls.framing_errors, ls.lost_packets)},
      {"I2C timing violations", std::to_string(done.at("i2c_violations").get<uint64_t>())},
      {"latency DRDY -> host, median / max (us)", fmt::format("{:.1f} / {:.1f}", lat_med, lat_max)}};
  if (decode_status) {
    const auto& d = decode_status->hall.status;
    run_rows.push_back({"FPGA decode status: commands accepted / rejected, baseline drops",
                   fmt::format("{} / {} (sent {}), {}", d.cmd_accepted, d.cmd_rejected,
                               setup.command_count, d.baseline_dropped)});
  }
  if (bus_status)
    for (size_t b = 0; b < bus_status->hall_buses.size(); ++b) {
      const auto& s = bus_status->hall_buses[b];
      run_rows.push_back({fmt::format("bus {}: NACKs / status errors / reply errors / recoveries / bus errors", b),
                     fmt::format("{} / {} / {} / {} / {}", s.nacks, s.status_errors, s.reply_errors,
                                 s.recoveries, s.bus_errors)});
    }
  page.table({"figure", "value"}, run_rows);
  const std::string html = (fs::path(out_dir) / "report.html").string();
  page.write(html);

  nlohmann::json sum = {{"scene", scene_file},      {"top", "hall_top"},
                        {"fpga_build", build.key},  {"fpga_clk_hz", build.clk_hz},
                        {"sim_s", sim_s},           {"cpu_s", cpu_s},
                        {"wall_s", wall_s},         {"cycles", cyc},
                        {"packets", rx.size()},     {"frames", frames.size()},
                        {"incomplete_frames", incomplete}, {"link_errors", link_errors},
                        {"i2c_violations", done.at("i2c_violations")},
                        {"steady_frames", scored},  {"commands_sent", setup.command_count},
                        {"latency_median_us", lat_med}, {"latency_max_us", lat_max}};
  if (decode_status) {
    sum["commands_accepted"] = decode_status->hall.status.cmd_accepted;
    sum["commands_rejected"] = decode_status->hall.status.cmd_rejected;
  }
  if (spec.decouple)
    sum["decouple"] = {{"fpga_shear", f_shear.get()}, {"fpga_normal", f_normal.get()},
                       {"golden_shear", g_shear.get()}, {"golden_normal", g_normal.get()},
                       {"fpga_frames", f_normal.n}};
  if (spec.ft) {
    nlohmann::json fw = nlohmann::json::array(), gw = nlohmann::json::array();
    for (int a = 0; a < 6; ++a) fw.push_back(f_w[size_t(a)].get()), gw.push_back(g_w[size_t(a)].get());
    sum["wrench"] = {{"fpga", fw}, {"golden", gw}, {"fpga_frames", f_w[0].n}};
  }
  if (spec.curve) {
    nlohmann::json fr = nlohmann::json::array(), gr = nlohmann::json::array(), n = nlohmann::json::array();
    for (int r = 0; r < 3; ++r)
      fr.push_back(f_range[size_t(r)].get()), gr.push_back(g_range[size_t(r)].get()), n.push_back(f_range[size_t(r)].n);
    sum["force_curve"] = {{"fpga", fr}, {"golden", gr}, {"fpga_frames", n}};
  }
  if (loc)
    sum["locate"] = {{"golden_single_mm", loc1.get()}, {"golden_multi_mm", locm.get()},
                     {"golden_rolling_mm", locroll.get()}, {"single_frames", loc1.n}};
  fmt::output_file((fs::path(out_dir) / "summary.json").string()).print("{}\n", sum.dump(2));

  fmt::print("scene {}: {} Hall sensors on {} bus(es), {:.3f} s simulated on the virtual board (Hall "
             "build {}) in {:.1f} s ({:.2f} simulated s per CPU s)\n",
             scene.name, ns, spec.nb, sim_s, build.key, wall_s, sim_s / cpu_s);
  fmt::print("FPGA: {} frames ({} incomplete), {} packets, {} link errors, {} I2C violations; "
             "{} commands sent\n",
             frames.size(), incomplete, rx.size(), link_errors,
             done.at("i2c_violations").get<uint64_t>(), setup.command_count);
  if (spec.decouple)
    fmt::print("decouple: FPGA shear {} normal {}; golden shear {} normal {} (mean |error| of full scale)\n",
               pct(f_shear.get()), pct(f_normal.get()), pct(g_shear.get()), pct(g_normal.get()));
  if (spec.ft) {
    double fa = 0, ga = 0;
    for (int a = 0; a < 6; ++a) fa += f_w[size_t(a)].get() / 6, ga += g_w[size_t(a)].get() / 6;
    fmt::print("wrench: six-axis average FPGA {}, golden {}\n", pct(fa), pct(ga));
  }
  if (spec.curve)
    fmt::print("force curve, ranges 1/2/3: FPGA {} / {} / {}, golden {} / {} / {} of the range's top\n",
               pct(f_range[0].get()), pct(f_range[1].get()), pct(f_range[2].get()),
               pct(g_range[0].get()), pct(g_range[1].get()), pct(g_range[2].get()));
  if (loc)
    fmt::print("locate (host-side, golden on the FPGA's readings): single presses {:.2f} mm over {} "
               "frames, multi-point {:.2f} mm, rolling ball {:.2f} mm\n",
               loc1.get(), loc1.n, locm.get(), locroll.get());
  if (lat_med >= 0)
    fmt::print("latency DRDY -> last byte on the host: median {:.0f} us, max {:.0f} us\n", lat_med, lat_max);
  fmt::print("report: {}\n", html);
  return sum;
}

int run_simulate_hall(const sim::Scene& scene, const std::string& scene_file,
                      const std::string& out_dir, const std::string& trace) {
  const vboard::HallBuild build = vboard::hall_build_for(scene);  // names a bad field
  const HallFpgaSetup setup = hall_simulation_setup(scene, build.spec);
  const std::string exe = vboard::board_executable(
      build, [](const std::string& m) { fmt::print(stderr, "eskin simulate: {}\n", m); });
  fs::create_directories(out_dir);

  vboard::VboardProcess board(exe, board_args(scene_file, trace, {setup.commands}));
  const BoardRun run = run_board(
      board, int(build.baud), {setup.commands}, size_t(scene.duration_s * 1e6),
      [](const Packet& p) { return p.type == link::kHallSamples ? long(p.t) : -1L; });
  report_hall(scene, scene_file, build, setup, run, out_dir);
  return board.wait() == 0 ? 0 : 1;
}

}  // namespace eskin::cli
