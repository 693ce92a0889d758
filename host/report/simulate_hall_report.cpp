#include "host/report/simulate_hall_report.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <memory>

#include "eskin/mlx90393_config.h"
#include "host/golden/contact_locate.h"
#include "host/golden/force_curve.h"
#include "host/golden/hall_baseline.h"
#include "host/hall/hall_chain.h"
#include "host/link/hall_packets.h"
#include "host/link/link_decoder.h"
#include "host/report/html_page.h"
#include "host/stream/packet_table.h"

namespace eskin::report {
namespace {

namespace fs = std::filesystem;
using link::Packet;

// hall_baseline's capture on the FPGA: the first 2^4 data readings of each
// sensor (rtl/hall_top.v); the golden side captures as many frames.
constexpr int kCaptureFrames = 16;

const char* kAxis[] = {"Fx", "Fy", "Fz", "Tx", "Ty", "Tz"};

// One HALL_SAMPLES frame and the decoding packets that follow it.
struct HallFrameRx {
  const Packet* samples = nullptr;
  double arrival_us = -1, last_arrival_us = -1;  // its last byte / its last packet's
  const Packet* decouple = nullptr;
  const Packet* wrench = nullptr;
  const Packet* forces = nullptr;
  double drdy_us = -1;  // the newest DRDY among its readings
};

// The Hall top's packets of a run, with their arrivals, grouped by frame.
// The frames point into `packets`: filled in place, never copied.
struct HallRx {
  std::vector<Packet> packets;
  std::vector<double> arrival;
  std::vector<HallFrameRx> frames;
  const Packet* bus_status = nullptr;
  const Packet* decode_status = nullptr;
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
struct TimeSeries {
  std::string label;
  int colour = 0, style = 0;  // 0 FPGA, 1 golden, 2 truth
  std::vector<double> t, v;
  void add(double ts, double val) { t.push_back(ts), v.push_back(val); }
};

// The errors against the truth, the time series and the latencies of the
// scored frames.
struct HallScores {
  Mean loc1, locm, locroll;
  Mean f_shear, f_normal, g_shear, g_normal;
  std::array<Mean, 6> f_w, g_w;
  std::array<Mean, 3> f_range, g_range;
  std::vector<double> latencies;
  std::vector<TimeSeries> force_s, field_s, torque_s, cell_s;
  size_t incomplete = 0, scored = 0;
};

// What the frames are scored with: the scene, the FPGA's configuration and
// the golden chain's.
struct HallChain {
  const sim::Scene& scene;
  const sim::HallWorld& world;
  const HallConfig& h;
  const sim::HallTopSpec& spec;
  const hall::HallFpgaSetup& setup;
  golden::Decoupled rest;
  // Seed 000: localisation is host-side by design (docs/hall_fpga.md): the
  // golden locator on the FPGA's readings.
  std::unique_ptr<golden::ContactLocator> loc;
};

// One frame being scored: its time, the truth and the golden baseline's
// field change at each sensor.
struct HallFrameScore {
  const HallFrameRx& f;
  double t;
  bool steady;
  int active;
  sim::HallTruth truth;
  const std::vector<Vec3>& delta;
};

double norm3(const Vec3& d) { return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]); }

// The run's Hall packets (other types ignored), with their arrivals.
void hall_packets(const stream::BoardRun& run, HallRx& hr) {
  for (size_t i = 0; i < run.rx.size(); ++i)
    if (link::is_hall_packet(run.rx[i].type)) {
      hr.packets.push_back(run.rx[i]);
      hr.arrival.push_back(run.arrival_us[i]);
    }
}

// The packet as `eskin stream` writes it (host/stream/packet_table.h: one
// row per reading, record or packet), with its arrival.
void write_ndjson(fmt::ostream& nd, const Packet& p, double arr) {
  if (const stream::PacketKind* kind = stream::find_kind(p.type)) {
    std::vector<stream::Row> rows;
    kind->rows(p, rows);
    for (const stream::Row& r : rows)
      nd.print("{{\"arrival_us\":{:.2f},{}\n", arr, stream::ndjson_line(*kind, r).substr(1));
  }
}

// Frames: HALL_SAMPLES and the decoding packets after it; every packet to
// fpga_packets.ndjson.
void group_frames(const sim::HallTopSpec& spec, const nlohmann::json& drdy,
                  const std::string& out_dir, HallRx& hr) {
  std::vector<size_t> read_k(spec.nb * spec.nsb, 0);  // data readings per slot so far
  auto nd = fmt::output_file((fs::path(out_dir) / "fpga_packets.ndjson").string());
  for (size_t i = 0; i < hr.packets.size(); ++i) {
    const Packet& p = hr.packets[i];
    const double arr = hr.arrival[i];
    write_ndjson(nd, p, arr);
    if (p.type == link::kHallSamples) {
      HallFrameRx f;
      f.samples = &p;
      f.arrival_us = f.last_arrival_us = arr;
      for (size_t s = 0; s < p.hall_samples.size() && s < read_k.size(); ++s) {
        if (!p.hall_samples[s].has_data()) continue;
        const size_t k = read_k[s]++;
        if (k < drdy[s].size()) f.drdy_us = std::max(f.drdy_us, drdy[s][k].get<double>() / 1000.0);
      }
      hr.frames.push_back(f);
      continue;
    }
    if (p.type == link::kHallBusStatus) hr.bus_status = &p;
    if (p.type == link::kHallDecodeStatus) hr.decode_status = &p;
    if (hr.frames.empty()) continue;
    HallFrameRx& f = hr.frames.back();
    if (p.type == link::kHallDecouple3) f.decouple = &p;
    else if (p.type == link::kHallWrench6) f.wrench = &p;
    else if (p.type == link::kHallForceCurve) f.forces = &p;
    else if (p.type != link::kHallDeltas) continue;
    f.last_arrival_us = arr;
  }
}

std::string model_label(int m) { return m == 0 ? "FPGA" : m == 1 ? "golden" : "truth"; }

// The report's time series: forces (FPGA, golden, truth per axis), torques,
// cell forces (FPGA, truth), the first ten sensors' field change.
void init_series(const sim::HallTopSpec& spec, size_t ns, HallScores& s) {
  for (int a = 0; a < 3 && (spec.decouple || spec.ft); ++a)
    for (int m = 0; m < 3; ++m)
      s.force_s.push_back({fmt::format("{} {}", model_label(m), kAxis[a]), a, m, {}, {}});
  for (int a = 3; a < 6 && spec.ft; ++a)
    for (int m = 0; m < 3; ++m)
      s.torque_s.push_back({fmt::format("{} {}", model_label(m), kAxis[a]), a, m, {}, {}});
  for (int c = 0; c < spec.nc && spec.curve; ++c)
    for (int m = 0; m < 3; m += 2)
      s.cell_s.push_back({fmt::format("{} cell {}", m == 0 ? "FPGA" : "truth", c), c, m, {}, {}});
  for (size_t i = 0; i < ns && i < 10; ++i)
    s.field_s.push_back({fmt::format("sensor {} |B - baseline|", i), int(i), 0, {}, {}});
}

// hall_frames.csv's header: each decoding block's columns, FPGA, golden, truth.
std::string csv_header(const HallChain& c) {
  std::string head = "t_s,arrival_us,drdy_to_host_us,steady";
  auto cols = [&](const std::vector<std::string>& names) {
    for (const char* m : {"fpga", "golden", "truth"})
      for (const auto& n : names) head += fmt::format(",{}_{}", m, n);
  };
  if (c.spec.decouple) cols({"fx_n", "fy_n", "fnormal_n"});
  if (c.spec.ft) cols({"fx_n", "fy_n", "fz_n", "tx_nmm", "ty_nmm", "tz_nmm"});
  if (c.h.wants(HallDecode::Locate)) head += ",golden_contacts_x_y_n";
  if (c.spec.curve) {
    std::vector<std::string> cells;
    for (int i = 0; i < c.spec.nc; ++i) cells.push_back(fmt::format("cell{}_n", i));
    cols(cells);
  }
  return head;
}

// The frame's readings in uT per scene sensor; false when a sensor's
// slot has no data.
bool frame_fields(const HallChain& c, const Packet& p, std::vector<Vec3>& ut) {
  const size_t ns = ut.size();
  bool complete = p.hall_samples.size() == size_t(c.spec.nb * c.spec.nsb);
  for (size_t i = 0; i < ns && complete; ++i) {
    const link::HallSample& hs = p.hall_samples[size_t(c.spec.slot[i])];
    complete = hs.has_data();
    const uint16_t code[3] = {hs.x, hs.y, hs.z};
    for (int a = 0; a < 3; ++a) ut[i][size_t(a)] = mlx90393::decode_uT(c.h.mlx, a, code[a]);
  }
  return complete;
}

// DECOUPLE: the FPGA's (Rx, Ry, Sz) and the golden chain's through the
// same force model, against the truth; the frame's CSV columns.
std::string score_decouple(const HallChain& c, const HallFrameScore& fr, HallScores& s) {
  const auto& dcal = c.setup.decouple;
  const double t = fr.t;
  const Vec3 ft{fr.truth.force_n[0], fr.truth.force_n[1], -fr.truth.force_n[2]};
  const golden::Decoupled gd = golden::hall_decouple(fr.delta[0], dcal.params);
  const Vec3 gf = gd.valid ? golden::decoupled_force(gd, c.rest, dcal.params) : Vec3{0, 0, 0};
  Vec3 ff{0, 0, 0};
  bool fvalid = false;
  if (fr.f.decouple && fr.f.decouple->hall.decouple.valid) {
    golden::Decoupled d;
    d.rx = fr.f.decouple->hall.decouple.rx / 16777216.0;  // Q8.24
    d.ry = fr.f.decouple->hall.decouple.ry / 16777216.0;
    d.sz = fr.f.decouple->hall.decouple.sz / 16777216.0;
    d.valid = fvalid = true;
    ff = golden::decoupled_force(d, c.rest, dcal.params);
  }
  for (int a = 0; a < 3; ++a) {
    if (fvalid) s.force_s[size_t(3 * a)].add(t, ff[size_t(a)]);
    s.force_s[size_t(3 * a + 1)].add(t, gf[size_t(a)]);
    s.force_s[size_t(3 * a + 2)].add(t, ft[size_t(a)]);
  }
  if (fr.steady && fvalid) {
    s.f_shear.add(std::fabs(ff[0] - ft[0]) / dcal.shear_fs_n);
    s.f_shear.add(std::fabs(ff[1] - ft[1]) / dcal.shear_fs_n);
    s.f_normal.add(std::fabs(ff[2] - ft[2]) / dcal.normal_fs_n);
  }
  if (fr.steady && gd.valid) {
    s.g_shear.add(std::fabs(gf[0] - ft[0]) / dcal.shear_fs_n);
    s.g_shear.add(std::fabs(gf[1] - ft[1]) / dcal.shear_fs_n);
    s.g_normal.add(std::fabs(gf[2] - ft[2]) / dcal.normal_fs_n);
  }
  return fmt::format(",{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}", ff[0],
                     ff[1], ff[2], gf[0], gf[1], gf[2], ft[0], ft[1], ft[2]);
}

// FT: the FPGA's wrench and the golden C on the same field changes, against
// the truth; the frame's CSV columns.
std::string score_wrench(const HallChain& c, const HallFrameScore& fr, HallScores& s) {
  const auto& wcal = c.setup.wrench;
  std::string fs_, gs_, ts_;
  golden::Vec9 b;
  for (int i = 0; i < 9; ++i) b(i) = fr.delta[size_t(i / 3)][size_t(i % 3)];
  const golden::Vec6 gw = golden::ft_apply(wcal.c, b);
  golden::Vec6 tw;
  tw << fr.truth.force_n[0], fr.truth.force_n[1], fr.truth.force_n[2], fr.truth.torque_nmm[0],
      fr.truth.torque_nmm[1], fr.truth.torque_nmm[2];
  const Packet* w = fr.f.wrench;
  for (int a = 0; a < 6; ++a) {
    auto& ser = a < 3 ? s.force_s : s.torque_s;
    const size_t k = size_t(3 * (a % 3));
    const double fw = w ? w->hall.wrench.w[a] / 1000.0 : 0;  // mN, mN*mm
    if (w) ser[k].add(fr.t, fw);
    ser[k + 1].add(fr.t, gw(a));
    ser[k + 2].add(fr.t, tw(a));
    fs_ += fmt::format(",{:.4f}", w ? fw : std::nan(""));
    gs_ += fmt::format(",{:.4f}", gw(a));
    ts_ += fmt::format(",{:.4f}", tw(a));
    if (!fr.steady) continue;
    if (w) s.f_w[size_t(a)].add(std::fabs(fw - tw(a)) / wcal.full_scale(a));
    s.g_w[size_t(a)].add(std::fabs(gw(a) - tw(a)) / wcal.full_scale(a));
  }
  return fs_ + gs_ + ts_;
}

// CURVE: each Stack cell's force, FPGA and golden curve, against the truth
// per sensitivity range; the frame's CSV columns.
std::string score_curve(const HallChain& c, const HallFrameScore& fr, HallScores& s) {
  std::string fs_, gs_, ts_;
  size_t ci = 0;
  for (size_t i = 0; i < c.h.cells.size(); ++i) {
    if (c.h.cells[i].kind != CellKind::Stack) continue;
    const size_t k = ci++;
    const double gf = golden::force_curve_apply(c.setup.curves[k], norm3(fr.delta[i]));
    const double tf = -fr.truth.cells[i].force_n[2];
    double ff = -1;
    if (fr.f.forces)
      for (const auto& r : fr.f.forces->hall.forces)
        if (r.cell == k && !(r.flags & link::HallSample::kReply)) ff = r.force_mn / 1000.0;
    if (k < size_t(c.spec.nc)) {
      if (ff >= 0) s.cell_s[2 * k].add(fr.t, ff);
      s.cell_s[2 * k + 1].add(fr.t, tf);
      fs_ += fmt::format(",{:.4f}", ff >= 0 ? ff : std::nan(""));
      gs_ += fmt::format(",{:.4f}", gf);
      ts_ += fmt::format(",{:.4f}", tf);
    }
    if (!fr.steady || tf <= 0) continue;
    const auto lock = c.h.cells[i].stack_lock_forces_n();
    const size_t r = size_t(std::lower_bound(lock.begin(), lock.end(), tf) - lock.begin());
    if (r >= 3) continue;
    if (ff >= 0) s.f_range[r].add(std::fabs(ff - tf) / lock[r]);
    s.g_range[r].add(std::fabs(gf - tf) / lock[r]);
  }
  return fs_ + gs_ + ts_;
}

// Seed 000: the golden locator's contacts, each true contact against the
// nearest found one; the frame's CSV column.
std::string score_locate(const HallChain& c, const HallFrameScore& fr, HallScores& s) {
  const size_t ns = fr.delta.size();
  Eigen::VectorXd x(Eigen::Index(3 * ns));
  for (size_t i = 0; i < ns; ++i)
    for (size_t a = 0; a < 3; ++a) x(Eigen::Index(3 * i + a)) = fr.delta[i][a];
  const auto found = c.loc->locate(x, std::max(1, fr.active), 0.05);
  std::string fx;
  for (const auto& g : found)
    fx += fmt::format("{}{:.2f};{:.2f};{:.3f}", fx.empty() ? "" : "|", g.x_mm, g.y_mm, g.force_n);
  const auto& rolls = c.scene.hall.rolls;
  const bool rolling = !rolls.empty() && rolls[0].envelope(fr.t) > 0;
  for (const auto& tc : fr.truth.contacts) {
    if (!fr.steady) break;
    double best = 1e300;
    for (const auto& g : found)
      best = std::min(best, std::hypot(g.x_mm - tc.point_mm[0], g.y_mm - tc.point_mm[1]));
    (rolling ? s.locroll : fr.truth.contacts.size() == 1 ? s.loc1 : s.locm).add(best);
  }
  return "," + fx;
}

// The golden chain on the FPGA's own readings, both against the truth:
// hall_frames.csv, one line per complete frame past the baseline capture.
void score_frames(const HallChain& c, const HallRx& hr, const std::string& out_dir,
                  HallScores& s) {
  const size_t ns = c.h.sensors.size();
  golden::HallBaseline base(ns, kCaptureFrames);
  if (c.spec.decouple) base.set(std::vector<Vec3>(ns, c.h.geomagnetic_ut));  // as the commands set it
  auto csv = fmt::output_file((fs::path(out_dir) / "hall_frames.csv").string());
  csv.print("{}\n", csv_header(c));
  std::vector<Vec3> delta;
  for (const HallFrameRx& f : hr.frames) {
    const Packet& p = *f.samples;
    const double t = p.t * 1e-6;
    const bool timed = f.drdy_us >= 0 && f.last_arrival_us >= 0;
    if (timed) s.latencies.push_back(f.last_arrival_us - f.drdy_us);
    std::vector<Vec3> ut(ns);
    if (!frame_fields(c, p, ut)) {
      ++s.incomplete;
      continue;
    }
    if (!base.push(ut, delta)) continue;
    bool steady = false;
    const int active = hall::active_stimuli(c.scene.hall, t, steady);
    const HallFrameScore fr{f, t, steady, active, c.world.truth(t), delta};
    for (size_t i = 0; i < s.field_s.size(); ++i) s.field_s[i].add(t, norm3(delta[i]));
    s.scored += steady;
    std::string line = fmt::format("{:.6f},{:.2f},{:.2f},{}", t, f.arrival_us,
                                   timed ? f.last_arrival_us - f.drdy_us : -1.0, steady ? 1 : 0);
    if (c.spec.decouple) line += score_decouple(c, fr, s);
    if (c.spec.ft) line += score_wrench(c, fr, s);
    if (c.spec.curve) line += score_curve(c, fr, s);
    if (c.loc) line += score_locate(c, fr, s);
    csv.print("{}\n", line);
  }
}

void series_chart(Page& page, const std::vector<TimeSeries>& ss, const std::string& y) {
  nlohmann::json sets = nlohmann::json::array();
  double lo = 0, hi = 0;  // the data's time extent: a tight axis
  bool any = false;
  for (const TimeSeries& s : ss)
    for (double t : s.t) {
      lo = any ? std::min(lo, t) : t;
      hi = any ? std::max(hi, t) : t;
      any = true;
    }
  for (const TimeSeries& s : ss) {
    nlohmann::json pts = nlohmann::json::array();
    for (size_t i = 0; i < s.t.size(); ++i) pts.push_back({{"x", s.t[i]}, {"y", s.v[i]}});
    nlohmann::json d = {{"label", s.label}, {"data", pts}, {"borderColor", kColours[s.colour % 10]},
                        {"pointRadius", 0}, {"borderWidth", s.style == 0 ? 1.5 : 1}};
    if (s.style == 1) d["borderDash"] = {5, 3};
    if (s.style == 2) d["borderDash"] = {1, 2};
    sets.push_back(d);
  }
  nlohmann::json x = {{"type", "linear"}, {"title", {{"display", true}, {"text", "time (s)"}}}};
  if (hi > lo) x.update({{"min", lo}, {"max", hi}, {"ticks", {{"includeBounds", false}}}});
  page.chart({{"type", "line"},
              {"data", {{"datasets", sets}}},
              {"options",
               {{"parsing", false},
                {"scales", {{"x", x}, {"y", {{"title", {{"display", true}, {"text", y}}}}}}}}}},
             340);
}

std::string pct(double v) { return fmt::format("{:.2f} %", 100 * v); }

double six_axis_average(const std::array<Mean, 6>& w) {
  double avg = 0;
  for (int a = 0; a < 6; ++a) avg += w[size_t(a)].get() / 6;
  return avg;
}

// The run's figures from the board's done line and the sorted latencies.
struct HallRunFigures {
  double sim_s, cpu_s, wall_s, cyc;
  double lat_med, lat_max;
  uint64_t link_errors;
};

HallRunFigures run_figures(const stream::BoardRun& run, std::vector<double>& latencies) {
  const nlohmann::json& done = run.done;
  const link::DecoderStats& ls = run.link;
  std::sort(latencies.begin(), latencies.end());
  return {done.at("sim_s"),
          done.at("cpu_s"),
          done.at("wall_s"),
          done.at("cycles"),
          latencies.empty() ? -1 : latencies[latencies.size() / 2],
          latencies.empty() ? -1 : latencies.back(),
          ls.crc_errors + ls.framing_errors + ls.payload_errors};
}

// Errors against the scene's truth, FPGA and golden, one column per figure
// of each decoding block.
void error_table(Page& page, const HallChain& c, const HallScores& s) {
  const auto& dcal = c.setup.decouple;
  page.heading("Errors against the scene's truth (steady frames: every active stimulus at full force)");
  std::vector<std::string> head{"model"};
  std::vector<std::string> frow{"FPGA (virtual board)"}, grow{"golden (on the FPGA's readings)"};
  if (c.spec.decouple) {
    head.insert(head.end(), {fmt::format("shear, mean |error| of {:.2f} N", dcal.shear_fs_n),
                             fmt::format("normal, of {:.2f} N", dcal.normal_fs_n)});
    frow.insert(frow.end(), {pct(s.f_shear.get()), pct(s.f_normal.get())});
    grow.insert(grow.end(), {pct(s.g_shear.get()), pct(s.g_normal.get())});
  }
  if (c.spec.ft) {
    for (int a = 0; a < 6; ++a) {
      head.push_back(fmt::format("{} (of its range)", kAxis[a]));
      frow.push_back(pct(s.f_w[size_t(a)].get()));
      grow.push_back(pct(s.g_w[size_t(a)].get()));
    }
    head.push_back("six-axis average");
    frow.push_back(pct(six_axis_average(s.f_w)));
    grow.push_back(pct(six_axis_average(s.g_w)));
  }
  if (c.spec.curve)
    for (int r = 0; r < 3; ++r) {
      head.push_back(fmt::format("force, range {} (of its top)", r + 1));
      frow.push_back(fmt::format("{} ({} frames)", pct(s.f_range[size_t(r)].get()), s.f_range[size_t(r)].n));
      grow.push_back(pct(s.g_range[size_t(r)].get()));
    }
  if (c.loc) {
    head.insert(head.end(), {"single press, position", "multi-point", "rolling ball"});
    frow.insert(frow.end(), {"host-side by design", "", ""});
    grow.insert(grow.end(), {fmt::format("{:.2f} mm ({} frames)", s.loc1.get(), s.loc1.n),
                             fmt::format("{:.2f} mm ({})", s.locm.get(), s.locm.n),
                             fmt::format("{:.2f} mm ({})", s.locroll.get(), s.locroll.n)});
  }
  head.push_back("frames scored");
  frow.push_back(std::to_string(s.scored));
  grow.push_back(std::to_string(s.scored));
  page.table(head, {frow, grow});
}

// Latency histogram, 50 us bins.
void latency_chart(Page& page, const std::vector<double>& latencies) {
  page.heading("Latency: a frame's newest DRDY to its last packet's last byte at the host");
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

// Force, torque and cell force over time, the field change at the sensors
// and the latency histogram.
void charts(Page& page, const HallScores& s) {
  if (!s.force_s.empty()) {
    page.heading("Force over time (FPGA solid, golden dashed, truth dotted)");
    series_chart(page, s.force_s, "force (N)");
  }
  if (!s.torque_s.empty()) series_chart(page, s.torque_s, "torque (N mm)");
  if (!s.cell_s.empty()) {
    page.heading("Cell forces (FPGA solid, truth dotted)");
    series_chart(page, s.cell_s, "force (N)");
  }
  page.heading("Field change at the sensors (baseline removed, from the FPGA's readings)");
  series_chart(page, s.field_s, "|B - baseline| (uT)");
  latency_chart(page, s.latencies);
}

// The run's figures: build, speed, frames, link, I2C, latency and the
// FPGA's decode and bus status.
void run_table(Page& page, const vboard::HallBuild& build, const hall::HallFpgaSetup& setup,
               const stream::BoardRun& run, const HallRx& hr, const HallScores& s,
               const HallRunFigures& r) {
  const link::DecoderStats& ls = run.link;
  page.heading("Run");
  std::vector<std::vector<std::string>> run_rows{
      {"fidelity level (eskin simulate --fidelity)", run.done.at("fidelity").get<std::string>()},
      {"FPGA build", build.key},
      {"simulated time (s)", fmt::format("{:.4f}", r.sim_s)},
      {"FPGA cycles", fmt::format("{:.0f}", r.cyc)},
      {"speed: simulated s per CPU s (board process)", fmt::format("{:.3f}", r.sim_s / r.cpu_s)},
      {"speed: simulated s per wall s", fmt::format("{:.3f}", r.sim_s / r.wall_s)},
      {"speed: FPGA cycles per CPU s", fmt::format("{:.3g}", r.cyc / r.cpu_s)},
      {"frames (HALL_SAMPLES) / incomplete", fmt::format("{} / {}", hr.frames.size(), s.incomplete)},
      {"packets received", std::to_string(hr.packets.size())},
      {"link: bytes / CRC errors / framing errors / lost packets",
       fmt::format("{} / {} / {} / {}", ls.bytes, ls.crc_errors, ls.framing_errors, ls.lost_packets)},
      {"I2C timing violations", std::to_string(run.done.at("i2c_violations").get<uint64_t>())},
      {"latency DRDY -> host, median / max (us)", fmt::format("{:.1f} / {:.1f}", r.lat_med, r.lat_max)}};
  if (hr.decode_status) {
    const auto& d = hr.decode_status->hall.status;
    run_rows.push_back({"FPGA decode status: commands accepted / rejected, baseline drops",
                        fmt::format("{} / {} (sent {}), {}", d.cmd_accepted, d.cmd_rejected,
                                    setup.command_count, d.baseline_dropped)});
  }
  if (hr.bus_status)
    for (size_t b = 0; b < hr.bus_status->hall_buses.size(); ++b) {
      const auto& st = hr.bus_status->hall_buses[b];
      run_rows.push_back({fmt::format("bus {}: NACKs / status errors / reply errors / recoveries / bus errors", b),
                          fmt::format("{} / {} / {} / {} / {}", st.nacks, st.status_errors,
                                      st.reply_errors, st.recoveries, st.bus_errors)});
    }
  run_rows.insert(run_rows.end(), run.line_rows.begin(), run.line_rows.end());  // faults
  page.table({"figure", "value"}, run_rows);
}

// report.html: the set-up, the errors, the charts and the run's figures.
std::string write_page(const HallChain& c, const std::string& scene_file,
                       const vboard::HallBuild& build, const stream::BoardRun& run,
                       const HallRx& hr, const HallScores& s, const HallRunFigures& r,
                       const std::string& out_dir) {
  Page page("eskin simulate: " + c.scene.name);
  page.text(fmt::format(
      "Hall skin: {} MLX90393 on {} I2C bus(es) of {} (rtl/hall_top.v build {} at {:.0f} MHz, "
      "400 kHz I2C, UART {:.0f} baud); {:.3f} s of the scene. The decoding's constants were "
      "calibrated by the golden chain and sent over the link ({} commands); the golden chain "
      "decoded the FPGA's own readings. Scene file: {}.",
      c.h.sensors.size(), c.spec.nb, c.spec.nsb, build.key, build.clk_hz / 1e6,
      double(build.baud), r.sim_s, c.setup.command_count, scene_file));
  error_table(page, c, s);
  charts(page, s);
  run_table(page, build, c.setup, run, hr, s, r);
  const std::string html = (fs::path(out_dir) / "report.html").string();
  page.write(html);
  return html;
}

nlohmann::json mean_list(const std::array<Mean, 6>& w) {
  nlohmann::json l = nlohmann::json::array();
  for (int a = 0; a < 6; ++a) l.push_back(w[size_t(a)].get());
  return l;
}

// summary.json: the run's figures and each decoding block's errors.
nlohmann::json summary(const HallChain& c, const std::string& scene_file,
                       const vboard::HallBuild& build, const stream::BoardRun& run,
                       const HallRx& hr, const HallScores& s, const HallRunFigures& r) {
  nlohmann::json sum = {{"scene", scene_file},      {"fidelity", run.done.at("fidelity")},
                        {"top", "hall_top"},
                        {"fpga_build", build.key},  {"fpga_clk_hz", build.clk_hz},
                        {"sim_s", r.sim_s},         {"cpu_s", r.cpu_s},
                        {"wall_s", r.wall_s},       {"cycles", r.cyc},
                        {"packets", hr.packets.size()}, {"frames", hr.frames.size()},
                        {"incomplete_frames", s.incomplete}, {"link_errors", r.link_errors},
                        {"i2c_violations", run.done.at("i2c_violations")},
                        {"steady_frames", s.scored},  {"commands_sent", c.setup.command_count},
                        {"latency_median_us", r.lat_med}, {"latency_max_us", r.lat_max}};
  if (hr.decode_status) {
    sum["commands_accepted"] = hr.decode_status->hall.status.cmd_accepted;
    sum["commands_rejected"] = hr.decode_status->hall.status.cmd_rejected;
  }
  if (c.spec.decouple)
    sum["decouple"] = {{"fpga_shear", s.f_shear.get()}, {"fpga_normal", s.f_normal.get()},
                       {"golden_shear", s.g_shear.get()}, {"golden_normal", s.g_normal.get()},
                       {"fpga_frames", s.f_normal.n}};
  if (c.spec.ft)
    sum["wrench"] = {{"fpga", mean_list(s.f_w)}, {"golden", mean_list(s.g_w)}, {"fpga_frames", s.f_w[0].n}};
  if (c.spec.curve) {
    nlohmann::json fr = nlohmann::json::array(), gr = nlohmann::json::array(), n = nlohmann::json::array();
    for (int i = 0; i < 3; ++i)
      fr.push_back(s.f_range[size_t(i)].get()), gr.push_back(s.g_range[size_t(i)].get()), n.push_back(s.f_range[size_t(i)].n);
    sum["force_curve"] = {{"fpga", fr}, {"golden", gr}, {"fpga_frames", n}};
  }
  if (c.loc)
    sum["locate"] = {{"golden_single_mm", s.loc1.get()}, {"golden_multi_mm", s.locm.get()},
                     {"golden_rolling_mm", s.locroll.get()}, {"single_frames", s.loc1.n}};
  return sum;
}

// The summary on stdout.
void print_summary(const HallChain& c, const vboard::HallBuild& build, const stream::BoardRun& run,
                   const HallRx& hr, const HallScores& s, const HallRunFigures& r,
                   const std::string& html) {
  fmt::print("scene {}: {} Hall sensors on {} bus(es), {:.3f} s simulated on the virtual board (Hall "
             "build {}, {} level) in {:.1f} s ({:.2f} simulated s per CPU s)\n",
             c.scene.name, c.h.sensors.size(), c.spec.nb, r.sim_s, build.key,
             run.done.at("fidelity").get<std::string>(), r.wall_s, r.sim_s / r.cpu_s);
  fmt::print("FPGA: {} frames ({} incomplete), {} packets, {} link errors, {} I2C violations; "
             "{} commands sent\n",
             hr.frames.size(), s.incomplete, hr.packets.size(), r.link_errors,
             run.done.at("i2c_violations").get<uint64_t>(), c.setup.command_count);
  if (c.spec.decouple)
    fmt::print("decouple: FPGA shear {} normal {}; golden shear {} normal {} (mean |error| of full scale)\n",
               pct(s.f_shear.get()), pct(s.f_normal.get()), pct(s.g_shear.get()), pct(s.g_normal.get()));
  if (c.spec.ft)
    fmt::print("wrench: six-axis average FPGA {}, golden {}\n", pct(six_axis_average(s.f_w)),
               pct(six_axis_average(s.g_w)));
  if (c.spec.curve)
    fmt::print("force curve, ranges 1/2/3: FPGA {} / {} / {}, golden {} / {} / {} of the range's top\n",
               pct(s.f_range[0].get()), pct(s.f_range[1].get()), pct(s.f_range[2].get()),
               pct(s.g_range[0].get()), pct(s.g_range[1].get()), pct(s.g_range[2].get()));
  if (c.loc)
    fmt::print("locate (host-side, golden on the FPGA's readings): single presses {:.2f} mm over {} "
               "frames, multi-point {:.2f} mm, rolling ball {:.2f} mm\n",
               s.loc1.get(), s.loc1.n, s.locm.get(), s.locroll.get());
  if (r.lat_med >= 0)
    fmt::print("latency DRDY -> last byte on the host: median {:.0f} us, max {:.0f} us\n", r.lat_med, r.lat_max);
  fmt::print("report: {}\n", html);
}

}  // namespace

nlohmann::json report_hall(const sim::Scene& scene, const std::string& scene_file,
                           const vboard::HallBuild& build, const hall::HallFpgaSetup& setup,
                           const stream::BoardRun& run, const std::string& out_dir) {
  fs::create_directories(out_dir);
  const sim::HallWorld world(scene.hall);
  HallChain c{scene, world, world.config(), build.spec, setup,
              golden::hall_decouple(setup.decouple.rest_film_ut, setup.decouple.params), nullptr};
  HallRx hr;
  hall_packets(run, hr);
  group_frames(c.spec, run.done.at("drdy_ns"), out_dir, hr);
  if (c.h.wants(HallDecode::Locate))
    c.loc = std::make_unique<golden::ContactLocator>(hall::calibrate_locator(world, scene.seed));
  HallScores s;
  init_series(c.spec, c.h.sensors.size(), s);
  score_frames(c, hr, out_dir, s);
  const HallRunFigures r = run_figures(run, s.latencies);
  const std::string html = write_page(c, scene_file, build, run, hr, s, r, out_dir);
  nlohmann::json sum = summary(c, scene_file, build, run, hr, s, r);
  if (!run.line.is_null()) sum["line"] = run.line;
  if (!run.board_faults.is_null()) sum["board_faults"] = run.board_faults;
  fmt::output_file((fs::path(out_dir) / "summary.json").string()).print("{}\n", sum.dump(2));
  print_summary(c, build, run, hr, s, r, html);
  return sum;
}

}  // namespace eskin::report
