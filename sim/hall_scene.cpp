#include "sim/hall_scene.h"

#include <algorithm>
#include <cmath>

#include "sim/scene_reader.h"

namespace eskin::sim {

// ---------------------------------------------------------------- stimuli

double trapezoid(double t, double t0, double ramp, double hold, double release) {
  double u = t - t0;
  if (u < 0) return 0;
  if (u < ramp) return u / ramp;
  u -= ramp;
  if (u < hold) return 1;
  u -= hold;
  if (u < release) return 1 - u / release;
  return 0;
}

double Envelope::at(double t) const { return trapezoid(t, t_start_s, ramp_s, hold_s, release_s); }

double HallRoll::length_mm() const {
  double l = 0;
  for (size_t i = 1; i < path_mm.size(); ++i)
    l += std::hypot(path_mm[i][0] - path_mm[i - 1][0], path_mm[i][1] - path_mm[i - 1][1]);
  return l;
}

void HallRoll::at(double t, std::array<double, 2>& p, std::array<double, 2>& dir) const {
  double s = std::max(0.0, (t - t_start_s) * speed_mm_s);
  p = path_mm.front();
  dir = {0, 0};
  for (size_t i = 1; i < path_mm.size(); ++i) {
    const double dx = path_mm[i][0] - path_mm[i - 1][0], dy = path_mm[i][1] - path_mm[i - 1][1];
    const double l = std::hypot(dx, dy);
    if (l <= 0) continue;
    dir = {dx / l, dy / l};
    if (s <= l || i + 1 == path_mm.size()) {
      const double u = std::min(s, l);
      p = {path_mm[i - 1][0] + dir[0] * u, path_mm[i - 1][1] + dir[1] * u};
      return;
    }
    s -= l;
  }
}

double HallRoll::envelope(double t) const {
  const double u = t - t_start_s, d = end_s() - t_start_s;
  if (u < 0 || u > d) return 0;
  if (ramp_s <= 0) return 1;
  return std::min({1.0, u / ramp_s, (d - u) / ramp_s});
}

double HallScene::surface_z_mm() const {
  double z = -1e300;
  for (const auto& c : config.cells) z = std::max(z, c.centre_mm[2]);
  return z;
}

void HallScene::loads_at(double t, std::vector<ContactLoad>& contacts,
                         std::vector<PlateWrench>& plate) const {
  contacts.clear();
  plate.clear();
  const double z = surface_z_mm();
  for (const auto& p : presses) {
    const double e = p.env.at(t);
    if (e <= 0) continue;
    contacts.push_back({{p.at_mm[0], p.at_mm[1], z},
                        {e * p.shear_n[0], e * p.shear_n[1], -e * p.normal_n},
                        p.radius_mm,
                        p.cell});
  }
  for (const auto& r : rolls) {
    const double e = r.envelope(t);
    if (e <= 0) continue;
    std::array<double, 2> at, dir;
    r.at(t, at, dir);
    contacts.push_back({{at[0], at[1], z},
                        {e * r.shear_n * dir[0], e * r.shear_n * dir[1], -e * r.normal_n},
                        r.radius_mm,
                        -1});
  }
  for (const auto& w : wrenches) {
    const double e = w.env.at(t);
    if (e <= 0) continue;
    PlateWrench pw;
    for (int k = 0; k < 3; ++k)
      pw.force_n[size_t(k)] = e * w.force_n[size_t(k)],
      pw.torque_nmm[size_t(k)] = e * w.torque_nmm[size_t(k)];
    plate.push_back(pw);
  }
}

// ---------------------------------------------------------------- parser

namespace scene_detail {
namespace {

Vec3 vec3(Reader& r, const YAML::Node& n, const std::string& f, const std::string& what) {
  if (!n.IsSequence() || n.size() != 3) r.fail(n, f, "expected " + what + ", got " + r.got(n));
  Vec3 v;
  for (size_t k = 0; k < 3; ++k) v[k] = r.number(n[k], f + "[" + std::to_string(k) + "]");
  return v;
}

std::array<double, 2> vec2(Reader& r, const YAML::Node& n, const std::string& f,
                           const std::string& what) {
  auto [a, b] = r.pair(n, f, what);
  return {r.number(a, f + "[0]"), r.number(b, f + "[1]")};
}

double pos(Reader& r, const YAML::Node& n, const std::string& f) {
  return r.ranged(n, f, 0, 1e9, true);
}

void require(Reader& r, const YAML::Node& n, const std::string& f,
             std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (!n[k]) r.fail(n, f + "." + k, "expected a value (required), got nothing");
}

template <class T>
int index_of(Reader& r, const YAML::Node& n, const std::string& f, const std::vector<T>& items,
             const std::string& what) {
  const std::string name = r.text(n, f);
  for (size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return int(i);
  std::string list;
  for (const auto& it : items) list += (list.empty() ? "" : ", ") + it.name;
  r.fail(n, f, "expected the name of one of the " + what + " (" + list + "), got '" + name + "'");
}

HallCell read_cell(Reader& r, const YAML::Node& n, const std::string& f) {
  HallCell c;
  r.mapping(n, f, {"name", "kind", "centre_mm", "footprint_mm", "k_normal_n_per_mm",
                   "k_shear_n_per_mm", "k_tilt_nmm_per_rad", "pillar_mm", "magnet_below_pivot_mm",
                   "layer_k_n_per_mm", "layer_travel_mm"});
  require(r, n, f, {"name", "kind", "centre_mm"});
  c.name = r.text(n["name"], f + ".name");
  const std::string kind = r.text(n["kind"], f + ".kind");
  if (kind == "film")
    c.kind = CellKind::Film;
  else if (kind == "pillar")
    c.kind = CellKind::Pillar;
  else if (kind == "stack")
    c.kind = CellKind::Stack;
  else
    r.fail(n["kind"], f + ".kind", "expected film, pillar or stack, got '" + kind + "'");
  c.centre_mm = vec3(r, n["centre_mm"], f + ".centre_mm", "[x, y, z] in mm");
  const std::vector<std::vector<const char*>> own = {
      {"footprint_mm", "k_normal_n_per_mm", "k_shear_n_per_mm"},
      {"k_normal_n_per_mm", "k_tilt_nmm_per_rad", "pillar_mm", "magnet_below_pivot_mm"},
      {"layer_k_n_per_mm", "layer_travel_mm"}};
  const auto& mine = own[size_t(c.kind)];
  for (const auto& kv : n) {
    const std::string key = kv.first.Scalar();
    if (key == "name" || key == "kind" || key == "centre_mm") continue;
    if (std::find_if(mine.begin(), mine.end(), [&](const char* k) { return key == k; }) ==
        mine.end())
      r.fail(kv.first, f + "." + key, "expected no " + key + " for a " + kind + " cell, got one");
  }
  for (const char* k : mine)
    if (!n[k]) r.fail(n, f + "." + k, std::string("expected a value for a ") + kind + " cell, got nothing");
  switch (c.kind) {
    case CellKind::Film:
      c.footprint_mm = vec2(r, n["footprint_mm"], f + ".footprint_mm", "[x, y] in mm");
      c.k_normal_n_per_mm = pos(r, n["k_normal_n_per_mm"], f + ".k_normal_n_per_mm");
      c.k_shear_n_per_mm = pos(r, n["k_shear_n_per_mm"], f + ".k_shear_n_per_mm");
      break;
    case CellKind::Pillar:
      c.k_normal_n_per_mm = pos(r, n["k_normal_n_per_mm"], f + ".k_normal_n_per_mm");
      c.k_tilt_nmm_per_rad = pos(r, n["k_tilt_nmm_per_rad"], f + ".k_tilt_nmm_per_rad");
      c.pillar_mm = pos(r, n["pillar_mm"], f + ".pillar_mm");
      c.magnet_below_pivot_mm = pos(r, n["magnet_below_pivot_mm"], f + ".magnet_below_pivot_mm");
      break;
    case CellKind::Stack:
      c.layer_k_n_per_mm = r.numbers(n["layer_k_n_per_mm"], f + ".layer_k_n_per_mm");
      c.layer_travel_mm = r.numbers(n["layer_travel_mm"], f + ".layer_travel_mm");
      break;
  }
  return c;
}

HallMagnet read_magnet(Reader& r, const YAML::Node& n, const std::string& f,
                       const std::vector<HallCell>& cells) {
  HallMagnet m;
  r.mapping(n, f, {"name", "shape", "size_mm", "centre_mm", "remanence_t", "cell"});
  require(r, n, f, {"name", "shape", "size_mm", "centre_mm", "remanence_t", "cell"});
  m.name = r.text(n["name"], f + ".name");
  const std::string shape = r.text(n["shape"], f + ".shape");
  if (shape == "box")
    m.shape = MagnetShape::Box;
  else if (shape == "cylinder")
    m.shape = MagnetShape::Cylinder;
  else if (shape == "centripetal_square")
    m.shape = MagnetShape::CentripetalSquare;
  else
    r.fail(n["shape"], f + ".shape",
           "expected box, cylinder or centripetal_square, got '" + shape + "'");
  if (m.shape == MagnetShape::Cylinder) {
    auto d = vec2(r, n["size_mm"], f + ".size_mm", "[diameter, height] in mm for a cylinder");
    m.size_mm = {d[0], d[0], d[1]};
  } else {
    m.size_mm = vec3(r, n["size_mm"], f + ".size_mm", "[x, y, z] extents in mm");
  }
  m.centre_mm = vec3(r, n["centre_mm"], f + ".centre_mm", "[x, y, z] in mm");
  m.remanence_t = r.number(n["remanence_t"], f + ".remanence_t");
  m.cell = index_of(r, n["cell"], f + ".cell", cells, "cells");
  return m;
}

HallSensor read_sensor(Reader& r, const YAML::Node& n, const std::string& f) {
  HallSensor s;
  r.mapping(n, f, {"name", "position_mm", "bus", "i2c_address", "mux", "mux_channel"});
  require(r, n, f, {"name", "position_mm"});
  s.name = r.text(n["name"], f + ".name");
  s.position_mm = vec3(r, n["position_mm"], f + ".position_mm", "[x, y, z] in mm");
  if (n["bus"]) s.bus = r.int_ranged(n["bus"], f + ".bus", 0, 15);
  // Address ranges are checked by validate() (its message shows them in hex).
  if (n["i2c_address"]) s.i2c_address = r.int_ranged(n["i2c_address"], f + ".i2c_address", 0, 127);
  if (n["mux"]) s.mux_address = r.int_ranged(n["mux"], f + ".mux", 0, 127);
  if (n["mux_channel"]) {
    if (!n["mux"]) r.fail(n["mux_channel"], f + ".mux_channel", "expected mux_channel only with mux, got it alone");
    s.mux_channel = r.int_ranged(n["mux_channel"], f + ".mux_channel", 0, 7);
  }
  return s;
}

void read_mlx(Reader& r, const YAML::Node& n, const std::string& f, mlx90393::Config& m) {
  r.mapping(n, f, {"hallconf", "gain_sel", "res", "osr", "dig_filt", "tcmp_en", "burst_data_rate"});
  if (n["hallconf"]) m.hallconf = r.int_ranged(n["hallconf"], f + ".hallconf", 0, 15);
  if (n["gain_sel"]) m.gain_sel = r.int_ranged(n["gain_sel"], f + ".gain_sel", 0, 7);
  if (n["res"]) m.res_x = m.res_y = m.res_z = r.int_ranged(n["res"], f + ".res", 0, 3);
  if (n["osr"]) m.osr = r.int_ranged(n["osr"], f + ".osr", 0, 3);
  if (n["dig_filt"]) m.dig_filt = r.int_ranged(n["dig_filt"], f + ".dig_filt", 0, 7);
  if (n["tcmp_en"]) m.tcmp_en = r.boolean(n["tcmp_en"], f + ".tcmp_en");
  if (n["burst_data_rate"])
    m.burst_data_rate = r.int_ranged(n["burst_data_rate"], f + ".burst_data_rate", 0, 63);
}

void read_locate(Reader& r, const YAML::Node& n, const std::string& f, HallConfig& h) {
  r.mapping(n, f, {"scan_pitch_mm", "scan_normal_n", "table_subdivision", "area_mm"});
  if (n["scan_pitch_mm"]) h.scan_pitch_mm = pos(r, n["scan_pitch_mm"], f + ".scan_pitch_mm");
  if (n["scan_normal_n"]) h.scan_normal_n = pos(r, n["scan_normal_n"], f + ".scan_normal_n");
  if (n["table_subdivision"])
    h.table_subdivision = r.int_ranged(n["table_subdivision"], f + ".table_subdivision", 1, 100);
  if (n["area_mm"]) {
    auto v = r.numbers(n["area_mm"], f + ".area_mm");
    if (v.size() != 4) r.fail(n["area_mm"], f + ".area_mm", "expected [x0, y0, x1, y1], got " + std::to_string(v.size()) + " numbers");
    h.area_mm = {v[0], v[1], v[2], v[3]};
  }
}

Envelope read_envelope(Reader& r, const YAML::Node& n, const std::string& f, double duration) {
  Envelope e;
  auto t = [&](const char* k, double& v) {
    if (n[k]) v = r.ranged(n[k], f + "." + k, 0, 1e6, false, ">= 0 s");
  };
  t("t_start_s", e.t_start_s);
  t("ramp_s", e.ramp_s);
  t("hold_s", e.hold_s);
  t("release_s", e.release_s);
  if (e.end_s() > duration + 1e-12)
    r.fail(n, f, "expected the stimulus to end by duration_s = " + num(duration) +
                     " s, got an end at " + num(e.end_s()) + " s (t_start_s + ramp_s + hold_s + release_s)");
  return e;
}

void inside(Reader& r, const YAML::Node& n, const std::string& f, const HallConfig& h,
            const std::array<double, 2>& p) {
  const auto& a = h.area_mm;
  if (p[0] < a[0] || p[0] > a[2] || p[1] < a[1] || p[1] > a[3])
    r.fail(n, f, "expected a point inside the skin area [" + num(a[0]) + ", " + num(a[1]) + ", " +
                     num(a[2]) + ", " + num(a[3]) + "] mm, got [" + num(p[0]) + ", " + num(p[1]) + "]");
}

HallPress read_press(Reader& r, const YAML::Node& n, const std::string& f, const HallConfig& h,
                     double duration) {
  HallPress p;
  r.mapping(n, f, {"at_mm", "cell", "normal_n", "shear_n", "radius_mm", "t_start_s", "ramp_s",
                   "hold_s", "release_s"});
  if (n["at_mm"] && n["cell"]) r.fail(n["cell"], f + ".cell", "expected either at_mm or cell, got both");
  if (n["at_mm"]) {
    p.at_mm = vec2(r, n["at_mm"], f + ".at_mm", "[x, y] in mm");
    inside(r, n["at_mm"], f + ".at_mm", h, p.at_mm);
  } else if (n["cell"]) {
    p.cell = index_of(r, n["cell"], f + ".cell", h.cells, "cells");
    p.at_mm = {h.cells[size_t(p.cell)].centre_mm[0], h.cells[size_t(p.cell)].centre_mm[1]};
  } else {
    r.fail(n, f + ".at_mm", "expected at_mm: [x, y] or cell: NAME, got neither");
  }
  if (!n["normal_n"]) r.fail(n, f + ".normal_n", "expected a normal force in N (required), got nothing");
  p.normal_n = r.ranged(n["normal_n"], f + ".normal_n", 0, 1e4);
  if (n["shear_n"]) p.shear_n = vec2(r, n["shear_n"], f + ".shear_n", "[x, y] in N");
  if (n["radius_mm"]) p.radius_mm = r.ranged(n["radius_mm"], f + ".radius_mm", 0.1, 100);
  p.env = read_envelope(r, n, f, duration);
  return p;
}

HallRoll read_roll(Reader& r, const YAML::Node& n, const std::string& f, const HallConfig& h,
                   double duration) {
  HallRoll b;
  r.mapping(n, f, {"path_mm", "speed_mm_s", "normal_n", "shear_n", "radius_mm", "t_start_s", "ramp_s"});
  require(r, n, f, {"path_mm", "speed_mm_s", "normal_n"});
  const YAML::Node& path = n["path_mm"];
  if (!path.IsSequence() || path.size() < 2)
    r.fail(path, f + ".path_mm", "expected a list of at least two [x, y] points, got " + r.got(path));
  for (size_t i = 0; i < path.size(); ++i) {
    const std::string fi = f + ".path_mm[" + std::to_string(i) + "]";
    r.note(path[i], fi);
    b.path_mm.push_back(vec2(r, path[i], fi, "[x, y] in mm"));
    inside(r, path[i], fi, h, b.path_mm.back());
  }
  if (!(b.length_mm() > 0)) r.fail(path, f + ".path_mm", "expected a path of non-zero length, got 0 mm");
  b.speed_mm_s = r.ranged(n["speed_mm_s"], f + ".speed_mm_s", 0, 1e4, true);
  b.normal_n = r.ranged(n["normal_n"], f + ".normal_n", 0, 1e4);
  if (n["shear_n"]) b.shear_n = r.number(n["shear_n"], f + ".shear_n");
  if (n["radius_mm"]) b.radius_mm = r.ranged(n["radius_mm"], f + ".radius_mm", 0.1, 100);
  if (n["t_start_s"]) b.t_start_s = r.ranged(n["t_start_s"], f + ".t_start_s", 0, 1e6, false, ">= 0 s");
  if (n["ramp_s"]) b.ramp_s = r.ranged(n["ramp_s"], f + ".ramp_s", 0, 1e6, false, ">= 0 s");
  if (b.end_s() > duration + 1e-12)
    r.fail(n, f, "expected the roll to end by duration_s = " + num(duration) + " s, got an end at " +
                     num(b.end_s()) + " s (t_start_s + path length / speed_mm_s)");
  return b;
}

HallWrench read_wrench(Reader& r, const YAML::Node& n, const std::string& f, const HallConfig& h,
                       double duration) {
  HallWrench w;
  r.mapping(n, f, {"force_n", "torque_nmm", "t_start_s", "ramp_s", "hold_s", "release_s"});
  if (!h.rigid_plate) r.fail(n, f, "expected a wrench only on a skin with rigid_plate: true, got rigid_plate: false");
  if (n["force_n"]) w.force_n = vec3(r, n["force_n"], f + ".force_n", "[fx, fy, fz] in N");
  if (n["torque_nmm"]) w.torque_nmm = vec3(r, n["torque_nmm"], f + ".torque_nmm", "[tx, ty, tz] in N*mm");
  w.env = read_envelope(r, n, f, duration);
  return w;
}

std::vector<HallDecode> read_decode(Reader& r, const YAML::Node& n, const std::string& f) {
  if (!n.IsSequence()) r.fail(n, f, "expected a list of baseline, decouple, wrench, force_curve, locate, got " + r.got(n));
  std::vector<HallDecode> out;
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string fi = f + "[" + std::to_string(i) + "]";
    const std::string v = r.text(n[i], fi);
    bool ok = false;
    for (HallDecode d : {HallDecode::Baseline, HallDecode::Decouple, HallDecode::Wrench,
                         HallDecode::ForceCurve, HallDecode::Locate})
      if (v == to_string(d)) out.push_back(d), ok = true;
    if (!ok) r.fail(n[i], fi, "expected baseline, decouple, wrench, force_curve or locate, got '" + v + "'");
  }
  return out;
}

template <class T, class F>
void read_list(Reader& r, const YAML::Node& n, const std::string& f, std::vector<T>& out, F one) {
  if (!n.IsSequence()) r.fail(n, f, "expected a list, got " + r.got(n));
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string fi = f + "[" + std::to_string(i) + "]";
    r.note(n[i], fi);
    out.push_back(one(n[i], fi));
  }
}

}  // namespace

HallScene read_hall(Reader& r, const YAML::Node& n, double duration) {
  HallScene sc;
  HallConfig& h = sc.config;
  const std::string f = "hall";
  r.mapping(n, f, {"geomagnetic_ut", "noise_rms_ut", "mlx", "decode", "rigid_plate", "cells", "magnets",
                   "sensors", "locate", "stimuli"});
  require(r, n, f, {"cells", "magnets", "sensors"});
  if (n["geomagnetic_ut"]) h.geomagnetic_ut = vec3(r, n["geomagnetic_ut"], f + ".geomagnetic_ut", "[x, y, z] in uT");
  if (n["noise_rms_ut"]) h.noise_rms_ut = vec3(r, n["noise_rms_ut"], f + ".noise_rms_ut", "[x, y, z] in uT RMS");
  if (n["mlx"]) read_mlx(r, n["mlx"], f + ".mlx", h.mlx);
  if (n["decode"]) h.decode = read_decode(r, n["decode"], f + ".decode");
  if (n["rigid_plate"]) h.rigid_plate = r.boolean(n["rigid_plate"], f + ".rigid_plate");
  if (n["locate"]) read_locate(r, n["locate"], f + ".locate", h);
  read_list(r, n["cells"], f + ".cells", h.cells,
            [&](const YAML::Node& x, const std::string& fi) { return read_cell(r, x, fi); });
  read_list(r, n["magnets"], f + ".magnets", h.magnets, [&](const YAML::Node& x, const std::string& fi) {
    return read_magnet(r, x, fi, h.cells);
  });
  read_list(r, n["sensors"], f + ".sensors", h.sensors,
            [&](const YAML::Node& x, const std::string& fi) { return read_sensor(r, x, fi); });
  try {
    validate(h, f);
  } catch (const ConfigError& e) {
    r.rethrow(e);
  }
  if (const YAML::Node& s = n["stimuli"]) {
    if (!s.IsSequence()) r.fail(s, f + ".stimuli", "expected a list of {press:}, {roll:} or {wrench:}, got " + r.got(s));
    for (size_t i = 0; i < s.size(); ++i) {
      const std::string fi = f + ".stimuli[" + std::to_string(i) + "]";
      const YAML::Node& item = s[i];
      r.note(item, fi);
      if (!item.IsMap() || item.size() != 1)
        r.fail(item, fi, "expected one of {press: {...}}, {roll: {...}} or {wrench: {...}}, got " + r.got(item));
      r.mapping(item, fi, {"press", "roll", "wrench"});
      if (item["press"]) sc.presses.push_back(read_press(r, item["press"], fi + ".press", h, duration));
      if (item["roll"]) sc.rolls.push_back(read_roll(r, item["roll"], fi + ".roll", h, duration));
      if (item["wrench"]) sc.wrenches.push_back(read_wrench(r, item["wrench"], fi + ".wrench", h, duration));
    }
  }
  return sc;
}

}  // namespace scene_detail
}  // namespace eskin::sim
