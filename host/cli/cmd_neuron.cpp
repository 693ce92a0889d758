// `eskin neuron --preset RS|IB|CH|FS|LTS|TC|RZ|RA --input step:AMP[@START_MS]
//  --duration MS [--dt MS] [--trace]`: drives one golden Izhikevich neuron
// (host/golden/izhikevich_layer.h) with a current step and prints NDJSON:
// one {"t_ms":..,"neuron":0} line per spike, with --trace also one
// {"t_ms":..,"input":..,"v":..,"u":..} line per step, and a final
// {"spikes":N,"mean_isi_ms":..,"var_isi_ms2":..} summary.
#include <fmt/core.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "eskin/neuron_config.h"
#include "eskin/skin_config.h"
#include "host/golden/izhikevich_layer.h"

namespace {

struct NeuronArgs {
  std::string preset = eskin::NeuronConfig{}.preset;
  std::string input;
  double duration_ms = 0;
  double dt_ms = eskin::NeuronConfig{}.dt_ms;
  bool trace = false;
};

struct StepInput {
  double amplitude = 0, start_ms = 0;
};

// Parses a whole string as a finite double; false if anything is left over.
bool parse_number(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

StepInput parse_input(const std::string& spec) {
  const std::string form =
      "expected step:AMPLITUDE[@START_MS] (input before the preset's gain K, start >= 0 ms; "
      "e.g. step:10@50), got '" + spec + "'";
  const std::string prefix = "step:";
  if (spec.compare(0, prefix.size(), prefix) != 0) throw eskin::ConfigError("--input", form);
  std::string rest = spec.substr(prefix.size());
  StepInput in;
  size_t at = rest.find('@');
  if (!parse_number(rest.substr(0, at), in.amplitude)) throw eskin::ConfigError("--input", form);
  if (at != std::string::npos &&
      (!parse_number(rest.substr(at + 1), in.start_ms) || in.start_ms < 0))
    throw eskin::ConfigError("--input", form);
  return in;
}

int run_neuron(const NeuronArgs& a) {
  eskin::IzhikevichParams p;
  try {
    p = eskin::golden::izhikevich_preset(a.preset);
  } catch (const eskin::ConfigError&) {  // re-say it in terms of the option
    std::string names;
    for (const auto& n : eskin::golden::izhikevich_preset_names())
      names += (names.empty() ? "" : "|") + n;
    throw eskin::ConfigError("--preset", "expected " + names + ", got '" + a.preset + "'");
  }
  const StepInput in = parse_input(a.input);
  if (!(a.duration_ms > 0 && a.duration_ms <= 1e7))
    throw eskin::ConfigError("--duration", "expected 0 < MS <= 1e7, got " + fmt::format("{}", a.duration_ms));
  if (!(a.dt_ms > 0 && a.dt_ms <= 10))
    throw eskin::ConfigError("--dt", "expected 0 < MS <= 10, got " + fmt::format("{}", a.dt_ms));

  eskin::golden::IzhikevichLayer layer(1, p, a.dt_ms);
  const long steps = std::lround(a.duration_ms / a.dt_ms);
  std::vector<double> times;
  std::vector<int> spiked;
  for (long k = 0; k < steps; ++k) {
    const double t = double(k) * a.dt_ms;  // start of this step
    const double x = t >= in.start_ms ? in.amplitude : 0.0;
    spiked.clear();
    layer.step(&x, spiked);
    if (a.trace)
      fmt::print("{{\"t_ms\":{},\"input\":{},\"v\":{},\"u\":{}}}\n", layer.time_ms(), x,
                 layer.v(0), layer.u(0));
    if (!spiked.empty()) {
      times.push_back(layer.time_ms());
      fmt::print("{{\"t_ms\":{},\"neuron\":0}}\n", layer.time_ms());
    }
  }
  const auto s = eskin::golden::spike_stats(times);
  fmt::print("{{\"spikes\":{},\"mean_isi_ms\":{},\"var_isi_ms2\":{}}}\n", s.count, s.mean_isi_ms,
             s.var_isi_ms2);
  return 0;
}

std::function<int()> setup_neuron(CLI::App& app) {
  auto args = std::make_shared<NeuronArgs>();
  CLI::App* sub = app.add_subcommand(
      "neuron", "Drive one golden Izhikevich neuron with a current step; print spikes as NDJSON");
  sub->add_option("--preset", args->preset,
                  "RS IB CH FS LTS TC RZ (Izhikevich 2003) or RA (thesis Table 4.1)")
      ->capture_default_str();
  sub->add_option("--input", args->input,
                  "step:AMPLITUDE[@START_MS]: input 0 before START_MS (default 0), then "
                  "AMPLITUDE; the current is I = K * input (K = 9 for RA, 1 otherwise)")
      ->required();
  sub->add_option("--duration", args->duration_ms, "Simulated time, ms")->required();
  sub->add_option("--dt", args->dt_ms, "Forward Euler step, ms")->capture_default_str();
  sub->add_flag("--trace", args->trace, "Also print t_ms, input, v, u after every step");
  return [args] { return run_neuron(*args); };
}

}  // namespace

ESKIN_COMMAND("neuron", setup_neuron);
