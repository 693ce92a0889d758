#include "sim/scene.h"

#include "sim/scene_reader.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace eskin::sim {

// ---------------------------------------------------------------- stimuli

double Press::envelope(double t) const { return trapezoid(t, t_start_s, ramp_s, hold_s, release_s); }

double Slide::envelope(double t) const {
  double u = t - t_start_s;
  if (u < 0 || u > duration_s) return 0;
  if (ramp_s <= 0) return 1;
  return std::min({1.0, u / ramp_s, (duration_s - u) / ramp_s});
}

void Slide::centre(double t, double& x, double& y) const {
  double s = duration_s > 0 ? std::clamp((t - t_start_s) / duration_s, 0.0, 1.0) : 0.0;
  x = x0 + s * (x1 - x0);
  y = y0 + s * (y1 - y0);
}

// Exact in y (a vertical chord of the disk clipped to the cell), midpoint
// rule over 64 strips in x: error well under 1% of the cell for r >= 0.1.
double disk_cover_fraction(double x, double y, double radius, int row, int col) {
  const double cx0 = col - 0.5, cx1 = col + 0.5, cy0 = row - 0.5, cy1 = row + 0.5;
  const double lo = std::max(cx0, x - radius), hi = std::min(cx1, x + radius);
  if (!(hi > lo) || y + radius <= cy0 || y - radius >= cy1) return 0;
  constexpr int kStrips = 64;
  const double w = (hi - lo) / kStrips;
  double area = 0;
  for (int k = 0; k < kStrips; ++k) {
    double dx = lo + (k + 0.5) * w - x;
    double h2 = radius * radius - dx * dx;
    if (h2 <= 0) continue;
    double h = std::sqrt(h2);
    double len = std::min(y + h, cy1) - std::max(y - h, cy0);
    if (len > 0) area += len * w;
  }
  return area;  // the cell's area is 1
}

// ---------------------------------------------------------------- errors

namespace {

std::string located(const std::string& file, int line, int col, const std::string& field,
                    const std::string& what) {
  std::string loc = file;
  if (line > 0) loc += ":" + std::to_string(line) + ":" + std::to_string(col);
  return loc + ": " + field + ": " + what;
}

}  // namespace

SceneError::SceneError(std::string file, int line, int col, std::string field,
                       const std::string& what)
    : std::runtime_error(located(file, line, col, field, what)),
      file_(std::move(file)),
      line_(line),
      col_(col),
      field_(std::move(field)) {}

namespace {

using namespace scene_detail;

// ---------------------------------------------------------------- sections

DecoderConfig read_decoder(Reader& r, const YAML::Node& n) {
  DecoderConfig d;
  if (!n.IsDefined()) return d;
  r.mapping(n, "decoder",
            {"window", "variant", "damping", "hann", "hop", "ghost_threshold", "ghost_onset"});
  if (n["window"]) d.window = r.int_ranged(n["window"], "decoder.window", 4, 4096);
  if (n["variant"]) {
    std::string v = r.text(n["variant"], "decoder.variant");
    try {
      d.variant = dft_variant_from_string(v);
    } catch (const ConfigError& e) {
      r.fail(n["variant"], "decoder.variant",
             "expected one of direct, recursive, damped, exact, ls, got '" + v + "'");
    }
  }
  if (n["damping"]) d.damping = r.ranged(n["damping"], "decoder.damping", 0, 1, true);
  if (n["hann"]) d.hann = r.boolean(n["hann"], "decoder.hann");
  if (n["hop"]) d.hop = r.int_ranged(n["hop"], "decoder.hop", 1, 1 << 20);
  if (n["ghost_threshold"])
    d.ghost_threshold = r.ranged(n["ghost_threshold"], "decoder.ghost_threshold", 0, 1);
  if (n["ghost_onset"])
    d.ghost_onset = r.ranged(n["ghost_onset"], "decoder.ghost_onset", 0, 1, true);
  return d;
}

Conductance read_conductance(Reader& r, const YAML::Node& n) {
  Conductance c;
  const std::string f = "skin.conductance";
  r.mapping(n, f, {"kind", "p_max_kpa", "p_half_kpa", "table"});
  if (!n["kind"]) r.fail(n, f + ".kind", "expected linear, saturating or table, got nothing");
  std::string kind = r.text(n["kind"], f + ".kind");
  const char* own = nullptr;
  if (kind == "linear") {
    c.kind = Conductance::Kind::Linear, own = "p_max_kpa";
  } else if (kind == "saturating") {
    c.kind = Conductance::Kind::Saturating, own = "p_half_kpa";
  } else if (kind == "table") {
    c.kind = Conductance::Kind::Table, own = "table";
  } else {
    r.fail(n["kind"], f + ".kind", "expected linear, saturating or table, got '" + kind + "'");
  }
  for (const char* k : {"p_max_kpa", "p_half_kpa", "table"})
    if (n[k] && std::string(k) != own)
      r.fail(n[k], f + "." + k, std::string("expected only ") + own + " with kind " + kind +
                                    ", got " + k);
  if (!n[own]) r.fail(n, f + "." + own, "expected a value for kind " + kind + ", got nothing");
  if (c.kind == Conductance::Kind::Linear)
    c.p_max_kpa = r.ranged(n[own], f + ".p_max_kpa", 0, INFINITY, true);
  if (c.kind == Conductance::Kind::Saturating)
    c.p_half_kpa = r.ranged(n[own], f + ".p_half_kpa", 0, INFINITY, true);
  if (c.kind == Conductance::Kind::Table) {
    const YAML::Node& t = n[own];
    if (!t.IsSequence()) r.fail(t, f + ".table", "expected a list of [p_kpa, g] pairs, got " + r.got(t));
    for (size_t i = 0; i < t.size(); ++i) {
      std::string fi = f + ".table[" + std::to_string(i) + "]";
      r.note(t[i], fi);
      auto [p, g] = r.pair(t[i], fi, "a [p_kpa, g] pair");
      c.table_p_kpa.push_back(r.ranged(p, fi, 0, INFINITY));
      c.table_g.push_back(r.ranged(g, fi, 0, 1));
    }
  }
  return c;
}

AdcConfig read_adc(Reader& r, const YAML::Node& n) {
  AdcConfig a;
  const std::string f = "skin.adc";
  r.mapping(n, f, {"rate_hz", "bits", "full_scale_v", "offset_v", "noise_rms_v"});
  if (n["rate_hz"]) a.rate_hz = r.ranged(n["rate_hz"], f + ".rate_hz", 0, 1e9, true);
  if (n["bits"]) a.bits = r.int_ranged(n["bits"], f + ".bits", 2, 24);
  if (n["full_scale_v"])
    a.full_scale_v = r.ranged(n["full_scale_v"], f + ".full_scale_v", 0, 1e3, true);
  a.offset_v = a.full_scale_v / 2;  // mid-scale unless given
  if (n["offset_v"])
    a.offset_v = r.ranged(n["offset_v"], f + ".offset_v", 0, a.full_scale_v, false,
                          "within [0, full_scale_v = " + num(a.full_scale_v) + "]");
  if (n["noise_rms_v"]) a.noise_rms_v = r.ranged(n["noise_rms_v"], f + ".noise_rms_v", 0, 1e3);
  return a;
}

SkinConfig read_skin(Reader& r, const YAML::Node& n, const DecoderConfig& dec) {
  SkinConfig s;
  const std::string f = "skin";
  r.mapping(n, f, {"rows", "cols", "carriers", "freq_error", "osc_amplitude_v", "amp_gain",
                   "conductance", "adc"});
  for (const char* k : {"rows", "cols", "carriers"})
    if (!n[k]) r.fail(n, f + "." + k, "expected a value (required), got nothing");
  s.rows = r.int_ranged(n["rows"], f + ".rows", 1, 256);
  s.cols = r.int_ranged(n["cols"], f + ".cols", 1, 256);
  if (n["adc"]) s.adc = read_adc(r, n["adc"]);
  if (n["osc_amplitude_v"])
    s.osc_amplitude_v = r.ranged(n["osc_amplitude_v"], f + ".osc_amplitude_v", 0, 1e3, true);
  if (n["amp_gain"]) s.amp_gain = r.ranged(n["amp_gain"], f + ".amp_gain", 0, 1e6, true);
  if (n["conductance"]) s.conductance = read_conductance(r, n["conductance"]);

  const YAML::Node& c = n["carriers"];
  const std::string cf = f + ".carriers";
  if (c.IsScalar()) {
    if (c.Scalar() != "auto")
      r.fail(c, cf, "expected 'auto' or a mapping {rows: [Hz...], cols: [Hz...]}, got " + r.got(c));
    std::vector<double> plan;
    try {
      plan = plan_carriers(s.carriers(), s.adc.rate_hz, dec.window);
    } catch (const ConfigError& e) {
      r.rethrow(e);
    }
    s.row_freq_hz.assign(plan.begin(), plan.begin() + s.rows);
    s.col_freq_hz.assign(plan.begin() + s.rows, plan.end());
  } else {
    if (!c.IsMap())
      r.fail(c, cf, "expected 'auto' or a mapping {rows: [Hz...], cols: [Hz...]}, got " + r.got(c));
    r.mapping(c, cf, {"rows", "cols"});
    for (const char* k : {"rows", "cols"})
      if (!c[k]) r.fail(c, cf + "." + k, "expected a list of frequencies in Hz, got nothing");
    s.row_freq_hz = r.numbers(c["rows"], cf + ".rows");
    s.col_freq_hz = r.numbers(c["cols"], cf + ".cols");
  }

  if (const YAML::Node& e = n["freq_error"]) {
    if (e.IsScalar())
      s.freq_error.assign(size_t(s.carriers()), r.number(e, f + ".freq_error"));
    else
      s.freq_error = r.numbers(e, f + ".freq_error");
  }
  return s;
}

NeuronConfig read_neuron(Reader& r, const YAML::Node& n, const SkinConfig& skin) {
  NeuronConfig c;
  c.dt_ms = 1000.0 / skin.adc.rate_hz;  // one ADC sample unless given
  if (!n.IsDefined()) return c;
  const std::string f = "neuron";
  r.mapping(n, f, {"preset", "dt_ms", "input", "input_scale", "layer2"});
  const auto preset = [&r](const YAML::Node& p, const std::string& field) {
    std::string v = r.text(p, field);
    const std::vector<std::string> presets = {"RS", "IB", "CH", "FS", "LTS", "TC", "RZ", "RA"};
    if (std::find(presets.begin(), presets.end(), v) == presets.end())
      r.fail(p, field, "expected one of RS, IB, CH, FS, LTS, TC, RZ, RA, got '" + v + "'");
    return v;
  };
  if (n["preset"]) c.preset = preset(n["preset"], f + ".preset");
  if (const YAML::Node l2 = n["layer2"]) {
    const std::string g = f + ".layer2";
    r.mapping(l2, g, {"preset", "centre", "surround"});
    if (l2["preset"]) c.layer2.preset = preset(l2["preset"], g + ".preset");
    if (l2["centre"]) c.layer2.centre = r.ranged(l2["centre"], g + ".centre", -100, 100, false);
    if (l2["surround"])
      c.layer2.surround = r.ranged(l2["surround"], g + ".surround", -100, 100, false);
  }
  if (n["dt_ms"]) c.dt_ms = r.ranged(n["dt_ms"], f + ".dt_ms", 0, 10, true);
  if (n["input"]) {
    std::string in = r.text(n["input"], f + ".input");
    if (in == "level")
      c.input = NeuronInput::Level;
    else if (in == "change")
      c.input = NeuronInput::RectifiedChange;
    else
      r.fail(n["input"], f + ".input", "expected level or change, got '" + in + "'");
  }
  if (n["input_scale"])
    c.input_scale = r.ranged(n["input_scale"], f + ".input_scale", 0, 1e6, true);
  return c;
}

// Times: >= 0 and finite.
double time_field(Reader& r, const YAML::Node& n, const std::string& field) {
  return r.ranged(n, field, 0, 1e6, false, ">= 0 s");
}

void read_position(Reader& r, const YAML::Node& n, const std::string& field,
                   const SkinConfig& skin, double& x, double& y) {
  auto [nx, ny] = r.pair(n, field, "[x, y] in taxel pitches (x along cols, y along rows)");
  x = r.ranged(nx, field + "[0]", -0.5, skin.cols - 0.5, false,
               "x within the matrix [-0.5, " + num(skin.cols - 0.5) + "]");
  y = r.ranged(ny, field + "[1]", -0.5, skin.rows - 0.5, false,
               "y within the matrix [-0.5, " + num(skin.rows - 0.5) + "]");
}

double radius_field(Reader& r, const YAML::Node& n, const std::string& field,
                    const SkinConfig& skin) {
  return r.ranged(n, field, 0.05, std::max(skin.rows, skin.cols), false);
}

void check_end(Reader& r, const YAML::Node& n, const std::string& field, double end,
               double duration, const std::string& sum) {
  if (end > duration + 1e-12)
    r.fail(n, field, "expected the stimulus to end by duration_s = " + num(duration) +
                         " s, got an end at " + num(end) + " s (" + sum + ")");
}

Press read_press(Reader& r, const YAML::Node& n, const std::string& f, const SkinConfig& skin,
                 double duration) {
  Press p;
  r.mapping(n, f, {"taxel", "at", "radius", "pressure_kpa", "t_start_s", "ramp_s", "hold_s",
                   "release_s"});
  if (n["taxel"] && n["at"]) r.fail(n["at"], f + ".at", "expected either taxel or at, got both");
  if (n["taxel"]) {
    auto [nr, nc] = r.pair(n["taxel"], f + ".taxel", "[row, col]");
    p.row = r.int_ranged(nr, f + ".taxel[0]", 0, skin.rows - 1);
    p.col = r.int_ranged(nc, f + ".taxel[1]", 0, skin.cols - 1);
    if (n["radius"])
      r.fail(n["radius"], f + ".radius", "expected radius only with at: [x, y], got it with taxel");
  } else if (n["at"]) {
    p.at_position = true;
    read_position(r, n["at"], f + ".at", skin, p.x, p.y);
    if (n["radius"]) p.radius = radius_field(r, n["radius"], f + ".radius", skin);
  } else {
    r.fail(n, f + ".taxel", "expected taxel: [row, col] or at: [x, y], got neither");
  }
  if (!n["pressure_kpa"]) r.fail(n, f + ".pressure_kpa", "expected a pressure (required), got nothing");
  p.pressure_kpa = r.ranged(n["pressure_kpa"], f + ".pressure_kpa", 0, 1e5, true);
  if (n["t_start_s"]) p.t_start_s = time_field(r, n["t_start_s"], f + ".t_start_s");
  if (n["ramp_s"]) p.ramp_s = time_field(r, n["ramp_s"], f + ".ramp_s");
  if (n["hold_s"]) p.hold_s = time_field(r, n["hold_s"], f + ".hold_s");
  if (n["release_s"]) p.release_s = time_field(r, n["release_s"], f + ".release_s");
  check_end(r, n, f, p.end_s(), duration, "t_start_s + ramp_s + hold_s + release_s");
  return p;
}

Slide read_slide(Reader& r, const YAML::Node& n, const std::string& f, const SkinConfig& skin,
                 double duration) {
  Slide s;
  r.mapping(n, f, {"from", "to", "radius", "pressure_kpa", "t_start_s", "duration_s", "ramp_s"});
  for (const char* k : {"from", "to", "pressure_kpa"})
    if (!n[k]) r.fail(n, f + "." + k, "expected a value (required), got nothing");
  read_position(r, n["from"], f + ".from", skin, s.x0, s.y0);
  read_position(r, n["to"], f + ".to", skin, s.x1, s.y1);
  if (n["radius"]) s.radius = radius_field(r, n["radius"], f + ".radius", skin);
  s.pressure_kpa = r.ranged(n["pressure_kpa"], f + ".pressure_kpa", 0, 1e5, true);
  if (n["t_start_s"]) s.t_start_s = time_field(r, n["t_start_s"], f + ".t_start_s");
  if (n["duration_s"])
    s.duration_s = r.ranged(n["duration_s"], f + ".duration_s", 0, 1e6, true);
  if (n["ramp_s"]) {
    s.ramp_s = time_field(r, n["ramp_s"], f + ".ramp_s");
    if (2 * s.ramp_s > s.duration_s)
      r.fail(n["ramp_s"], f + ".ramp_s",
             "expected at most duration_s / 2 = " + num(s.duration_s / 2) + ", got " + num(s.ramp_s));
  } else {
    s.ramp_s = std::min(s.ramp_s, s.duration_s / 2);
  }
  check_end(r, n, f, s.end_s(), duration, "t_start_s + duration_s");
  return s;
}

void read_stimuli(Reader& r, const YAML::Node& n, Scene& sc) {
  if (!n.IsSequence())
    r.fail(n, "stimuli", "expected a list of {press: {...}} or {slide: {...}}, got " + r.got(n));
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string f = "stimuli[" + std::to_string(i) + "]";
    const YAML::Node& item = n[i];
    r.note(item, f);
    if (!item.IsMap() || item.size() != 1)
      r.fail(item, f, "expected one of {press: {...}} or {slide: {...}}, got " + r.got(item));
    r.mapping(item, f, {"press", "slide"});
    if (item["press"])
      sc.presses.push_back(read_press(r, item["press"], f + ".press", sc.skin, sc.duration_s));
    else
      sc.slides.push_back(read_slide(r, item["slide"], f + ".slide", sc.skin, sc.duration_s));
  }
}

Outputs read_outputs(Reader& r, const YAML::Node& n) {
  Outputs o;
  if (!n.IsDefined()) return o;
  if (!n.IsSequence())
    r.fail(n, "outputs", "expected a list of amplitudes, taxels, spikes, got " + r.got(n));
  o = Outputs{false, false, false};
  for (size_t i = 0; i < n.size(); ++i) {
    std::string f = "outputs[" + std::to_string(i) + "]";
    std::string v = r.text(n[i], f);
    if (v == "amplitudes")
      o.amplitudes = true;
    else if (v == "taxels")
      o.taxels = true;
    else if (v == "spikes")
      o.spikes = true;
    else
      r.fail(n[i], f, "expected amplitudes, taxels or spikes, got '" + v + "'");
  }
  return o;
}

std::string stem(const std::string& path) {
  std::string s = path.substr(path.find_last_of('/') + 1);
  return s.substr(0, s.find('.'));
}

void validate_all(Reader& r, const SkinConfig& skin, const DecoderConfig* dec) {
  try {
    validate(skin, "skin");
    if (dec) validate(*dec, skin, "decoder");
  } catch (const ConfigError& e) {
    r.rethrow(e);
  }
}

}  // namespace

// ---------------------------------------------------------------- loaders

Scene parse_scene(const std::string& text, const std::string& file) {
  Reader r(file);
  const YAML::Node root = parse_yaml(text, file);
  if (!root.IsMap()) r.fail(root, "(scene)", "expected a mapping of scene fields, got " + r.got(root));
  r.mapping(root, "", {"name", "seed", "duration_s", "skin", "decoder", "neuron", "stimuli",
                       "outputs", "hall"});
  if (!root["duration_s"]) r.fail(root, "duration_s", "expected a value (required), got nothing");
  if (!root["skin"] && !root["hall"])
    r.fail(root, "skin", "expected a skin: (DTMF) or hall: (magnetic) section, got neither");

  Scene sc;
  sc.file = file;
  sc.name = root["name"] ? r.text(root["name"], "name") : stem(file);
  if (const YAML::Node& s = root["seed"]) {
    if (!s.IsScalar() || s.Scalar().empty() || s.Scalar()[0] == '-' ||
        !YAML::convert<uint64_t>::decode(s, sc.seed))
      r.fail(s, "seed", "expected an integer >= 0, got " + r.got(s));
  }
  sc.has_skin = bool(root["skin"]);
  if (!sc.has_skin) {
    // A Hall-only scene: the DTMF-only sections have nothing to act on.
    for (const char* k : {"decoder", "neuron", "stimuli", "outputs"})
      if (root[k]) r.fail(root[k], k, std::string("expected ") + k + " only with a skin: section, got it without one");
    sc.duration_s = r.ranged(root["duration_s"], "duration_s", 0, 1e6, true);
    sc.has_hall = true;
    sc.hall = read_hall(r, root["hall"], sc.duration_s);
    return sc;
  }
  sc.decoder = read_decoder(r, root["decoder"]);
  sc.skin = read_skin(r, root["skin"], sc.decoder);
  validate_all(r, sc.skin, &sc.decoder);
  sc.neuron = read_neuron(r, root["neuron"], sc.skin);
  sc.duration_s = r.ranged(root["duration_s"], "duration_s", 0, 1e9 / sc.skin.adc.rate_hz, true,
                           "(0, " + num(1e9 / sc.skin.adc.rate_hz) + "] s (at most 1e9 samples)");
  if (root["stimuli"] && !root["stimuli"].IsNull()) read_stimuli(r, root["stimuli"], sc);
  sc.outputs = read_outputs(r, root["outputs"]);
  if (root["hall"]) {
    sc.has_hall = true;
    sc.hall = read_hall(r, root["hall"], sc.duration_s);
  }
  return sc;
}

Scene load_scene(const std::string& path) { return parse_scene(read_file(path), path); }

SkinConfig parse_skin(const std::string& text, const std::string& file) {
  Reader r(file);
  const YAML::Node root = parse_yaml(text, file);
  if (!root.IsMap() || !root["skin"])
    r.fail(root, "skin", "expected a file with a top-level skin: mapping, got " +
                             (root.IsMap() ? std::string("none") : r.got(root)));
  DecoderConfig dec = read_decoder(r, root["decoder"]);
  SkinConfig skin = read_skin(r, root["skin"], dec);
  validate_all(r, skin, root["decoder"] ? &dec : nullptr);
  return skin;
}

SkinConfig load_skin(const std::string& path) { return parse_skin(read_file(path), path); }

}  // namespace eskin::sim
