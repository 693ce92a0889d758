#include "eskin/hall_config.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>

namespace eskin {

double HallCell::stack_compression_mm(double f) const {
  double d = 0;
  for (size_t i = 0; i < layer_k_n_per_mm.size(); ++i)
    d += std::min(std::max(f, 0.0) / layer_k_n_per_mm[i], layer_travel_mm[i]);
  return d;
}

std::vector<double> HallCell::stack_lock_forces_n() const {
  std::vector<double> f;
  for (size_t i = 0; i < layer_k_n_per_mm.size(); ++i)
    f.push_back(layer_k_n_per_mm[i] * layer_travel_mm[i]);
  return f;
}

bool HallConfig::wants(HallDecode d) const {
  return std::find(decode.begin(), decode.end(), d) != decode.end();
}

int HallConfig::bus_count() const {
  int n = 0;
  for (const auto& s : sensors) n = std::max(n, s.bus + 1);
  return n;
}

Vec3 scaled_noise_ut(const Vec3& noise, const mlx90393::Config& from, const mlx90393::Config& to) {
  auto count = [](const mlx90393::Config& c) {
    return double(1 << c.osr) * (2.0 + double(1 << c.dig_filt));
  };
  const double k = std::sqrt(count(from) / count(to));
  return {noise[0] * k, noise[1] * k, noise[2] * k};
}

const char* to_string(MagnetShape s) {
  switch (s) {
    case MagnetShape::Box: return "box";
    case MagnetShape::Cylinder: return "cylinder";
    case MagnetShape::CentripetalSquare: return "centripetal_square";
  }
  return "?";
}

const char* to_string(CellKind k) {
  switch (k) {
    case CellKind::Film: return "film";
    case CellKind::Pillar: return "pillar";
    case CellKind::Stack: return "stack";
  }
  return "?";
}

const char* to_string(HallDecode d) {
  switch (d) {
    case HallDecode::Baseline: return "baseline";
    case HallDecode::Decouple: return "decouple";
    case HallDecode::Wrench: return "wrench";
    case HallDecode::ForceCurve: return "force_curve";
    case HallDecode::Locate: return "locate";
  }
  return "?";
}

namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string at(const std::string& f, size_t i) { return f + "[" + std::to_string(i) + "]"; }

void positive(double v, const std::string& field) {
  if (!(v > 0) || !std::isfinite(v)) throw ConfigError(field, "expected > 0, got " + num(v));
}

void validate_magnet(const HallMagnet& m, size_t cells, const std::string& f) {
  for (int k = 0; k < 3; ++k) positive(m.size_mm[size_t(k)], at(f + ".size_mm", size_t(k)));
  if (m.shape == MagnetShape::CentripetalSquare && m.size_mm[0] != m.size_mm[1])
    throw ConfigError(f + ".size_mm", "expected a square (equal x and y sides) for a "
                                      "centripetal film, got " + num(m.size_mm[0]) + " x " +
                                          num(m.size_mm[1]));
  if (!(std::fabs(m.remanence_t) > 0 && std::fabs(m.remanence_t) <= 2))
    throw ConfigError(f + ".remanence_t",
                      "expected 0 < |Br| <= 2 T (NdFeB is about 1.3 T), got " + num(m.remanence_t));
  if (m.cell < 0 || size_t(m.cell) >= cells)
    throw ConfigError(f + ".cell", "expected the name of one of the " + std::to_string(cells) +
                                       " cells, got index " + std::to_string(m.cell));
}

void validate_cell(const HallCell& c, const std::string& f) {
  switch (c.kind) {
    case CellKind::Film:
      positive(c.footprint_mm[0], f + ".footprint_mm[0]");
      positive(c.footprint_mm[1], f + ".footprint_mm[1]");
      positive(c.k_normal_n_per_mm, f + ".k_normal_n_per_mm");
      positive(c.k_shear_n_per_mm, f + ".k_shear_n_per_mm");
      break;
    case CellKind::Pillar:
      positive(c.k_normal_n_per_mm, f + ".k_normal_n_per_mm");
      positive(c.k_tilt_nmm_per_rad, f + ".k_tilt_nmm_per_rad");
      positive(c.pillar_mm, f + ".pillar_mm");
      positive(c.magnet_below_pivot_mm, f + ".magnet_below_pivot_mm");
      break;
    case CellKind::Stack:
      if (c.layer_k_n_per_mm.empty())
        throw ConfigError(f + ".layer_k_n_per_mm", "expected at least one layer, got none");
      if (c.layer_travel_mm.size() != c.layer_k_n_per_mm.size())
        throw ConfigError(f + ".layer_travel_mm",
                          "expected one travel per layer (" +
                              std::to_string(c.layer_k_n_per_mm.size()) + "), got " +
                              std::to_string(c.layer_travel_mm.size()));
      for (size_t i = 0; i < c.layer_k_n_per_mm.size(); ++i) {
        positive(c.layer_k_n_per_mm[i], at(f + ".layer_k_n_per_mm", i));
        positive(c.layer_travel_mm[i], at(f + ".layer_travel_mm", i));
      }
      {
        auto lock = c.stack_lock_forces_n();
        for (size_t i = 1; i < lock.size(); ++i)
          if (!(lock[i] > lock[i - 1]))
            throw ConfigError(at(f + ".layer_k_n_per_mm", i),
                              "expected layers to lock in order (k*travel ascending), got " +
                                  num(lock[i]) + " N after " + num(lock[i - 1]) + " N");
      }
      break;
  }
}

void validate_sensor(const HallSensor& s, const std::string& f) {
  if (s.bus < 0 || s.bus > 15)
    throw ConfigError(f + ".bus", "expected 0..15, got " + std::to_string(s.bus));
  // MLX90393 addresses: 0x0C..0x0F, 0x10..0x13, 0x14..0x17, 0x18..0x1B by
  // variant and A1/A0 pins.
  if (s.i2c_address < 0x0C || s.i2c_address > 0x1B)
    throw ConfigError(f + ".i2c_address",
                      "expected an MLX90393 address 0x0C..0x1B, got " + std::to_string(s.i2c_address));
  if (s.mux_address != -1 && (s.mux_address < 0x70 || s.mux_address > 0x77))
    throw ConfigError(f + ".mux", "expected a TCA9548A address 0x70..0x77, got " +
                                      std::to_string(s.mux_address));
  if (s.mux_address != -1 && (s.mux_channel < 0 || s.mux_channel > 7))
    throw ConfigError(f + ".mux_channel", "expected 0..7, got " + std::to_string(s.mux_channel));
}

}  // namespace

void validate(const HallConfig& h, const std::string& p) {
  if (h.cells.empty()) throw ConfigError(p + ".cells", "expected at least one cell, got none");
  if (h.magnets.empty()) throw ConfigError(p + ".magnets", "expected at least one magnet, got none");
  if (h.sensors.empty()) throw ConfigError(p + ".sensors", "expected at least one sensor, got none");
  for (size_t i = 0; i < h.cells.size(); ++i) validate_cell(h.cells[i], at(p + ".cells", i));
  for (size_t i = 0; i < h.magnets.size(); ++i)
    validate_magnet(h.magnets[i], h.cells.size(), at(p + ".magnets", i));
  // Two devices on one bus segment may not share an address.
  std::set<std::pair<std::pair<int, int>, std::pair<int, int>>> used;
  for (size_t i = 0; i < h.sensors.size(); ++i) {
    const HallSensor& s = h.sensors[i];
    const std::string f = at(p + ".sensors", i);
    validate_sensor(s, f);
    const int ch = s.mux_address == -1 ? -1 : s.mux_channel;
    if (!used.insert({{s.bus, s.mux_address}, {ch, s.i2c_address}}).second)
      throw ConfigError(f + ".i2c_address",
                        "expected an address unique on bus " + std::to_string(s.bus) +
                            (ch >= 0 ? " mux channel " + std::to_string(ch) : "") + ", got " +
                            std::to_string(s.i2c_address) + " a second time");
  }
  mlx90393::validate(h.mlx, p + ".mlx");
  for (size_t k = 0; k < 3; ++k)
    if (!(h.noise_rms_ut[k] >= 0))
      throw ConfigError(at(p + ".noise_rms_ut", k), "expected >= 0, got " + num(h.noise_rms_ut[k]));
  if (!h.wrench_matrix.empty() && h.wrench_matrix.size() != 54)
    throw ConfigError(p + ".wrench_matrix", "expected 6 rows of 9 (54 numbers), got " +
                                                std::to_string(h.wrench_matrix.size()));
  if (h.wants(HallDecode::Wrench) && h.sensors.size() != 3)
    throw ConfigError(p + ".decode", "expected wrench only with exactly 3 sensors (C is 6x9), got " +
                                         std::to_string(h.sensors.size()) + " sensors");
  if (h.wants(HallDecode::Decouple) && h.sensors.size() != 1)
    throw ConfigError(p + ".decode", "expected decouple only with exactly 1 sensor, got " +
                                         std::to_string(h.sensors.size()));
  for (size_t c = 0; c < h.force_curves.size(); ++c) {
    const ForceCurve& fc = h.force_curves[c];
    const std::string f = at(p + ".force_curves", c);
    if (fc.db_ut.size() < 2 || fc.db_ut.size() != fc.force_n.size())
      throw ConfigError(f, "expected at least two [db_ut, force_n] breakpoints, got " +
                               std::to_string(fc.db_ut.size()));
    for (size_t i = 1; i < fc.db_ut.size(); ++i)
      if (!(fc.db_ut[i] > fc.db_ut[i - 1]))
        throw ConfigError(at(f, i), "expected db_ut ascending, got " + num(fc.db_ut[i]) +
                                        " after " + num(fc.db_ut[i - 1]));
  }
  positive(h.scan_pitch_mm, p + ".locate.scan_pitch_mm");
  positive(h.scan_normal_n, p + ".locate.scan_normal_n");
  if (h.table_subdivision < 1 || h.table_subdivision > 100)
    throw ConfigError(p + ".locate.table_subdivision",
                      "expected 1..100, got " + std::to_string(h.table_subdivision));
  if (!(h.area_mm[2] > h.area_mm[0] && h.area_mm[3] > h.area_mm[1]))
    throw ConfigError(p + ".locate.area_mm", "expected [x0, y0, x1, y1] with x1 > x0 and y1 > y0");
}

}  // namespace eskin
