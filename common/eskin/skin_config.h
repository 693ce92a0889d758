// Shared configuration of a DTMF (spatial-frequency) skin and its decoder.
// The one place where a skin's sizes, carriers and rates are described; the
// scene loader (sim/), the golden model (host/golden/) and the CLI all use
// these types. hls/ does not include this file: kernels stand alone.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace eskin {

// A configuration error names the field (a dotted path, e.g.
// "skin.carriers.rows[2]") and says what was expected.
class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string field, const std::string& what)
      : std::runtime_error(field + ": " + what), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

struct AdcConfig {
  double rate_hz = 35000.0;   // sample rate
  int bits = 10;              // resolution; codes are unsigned 0 .. 2^bits-1
  double full_scale_v = 3.3;  // input range [0, full_scale_v]
  double offset_v = 1.65;     // analog bias of the summed signal at the input
  double noise_rms_v = 0.0;   // white Gaussian noise before quantisation

  int max_code() const { return (1 << bits) - 1; }
  double lsb_v() const { return full_scale_v / double(1 << bits); }
  // Code of the bias point: decoders subtract it before any DFT.
  double mid_code() const { return offset_v / lsb_v(); }
};

// g(p): the fraction (0..1) of a carrier that a taxel passes to the common
// conductor under pressure p (kPa). Monotonic, g(0) = 0.
struct Conductance {
  enum class Kind { Linear, Saturating, Table };
  Kind kind = Kind::Saturating;
  double p_max_kpa = 100.0;   // Linear: g = min(1, p / p_max)
  double p_half_kpa = 50.0;   // Saturating: g = p / (p + p_half)
  std::vector<double> table_p_kpa;  // Table: piecewise linear, p ascending,
  std::vector<double> table_g;      //   starts at (0, 0), g non-decreasing

  double g(double p_kpa) const;
  // Pressure that gives conductance fraction g (clamped to the curve's range).
  double inverse(double g) const;
};

struct SkinConfig {
  int rows = 3;
  int cols = 3;
  std::vector<double> row_freq_hz;  // nominal carrier of each row
  std::vector<double> col_freq_hz;  // nominal carrier of each column
  // Relative frequency error of each real oscillator, rows then columns
  // (actual = nominal * (1 + err)); empty means all exact.
  std::vector<double> freq_error;
  double osc_amplitude_v = 1.0;     // oscillator amplitude, V peak
  double amp_gain = 0.5;            // summing amplifier gain, V/V
  Conductance conductance;
  AdcConfig adc;

  int carriers() const { return rows + cols; }
  // Nominal carrier frequencies, rows first then columns.
  std::vector<double> carrier_freqs_hz() const;
  // Actual oscillator frequencies (nominal with freq_error applied).
  std::vector<double> actual_freqs_hz() const;
  // Each carrier's name for charts, rows first: "row 0 · 1209 Hz".
  std::vector<std::string> carrier_labels() const;
  // Amplitude in ADC LSB that one carrier reaches at the ADC when the taxels
  // on its line pass a total conductance fraction of 1.
  double full_carrier_lsb() const {
    return osc_amplitude_v * amp_gain / adc.lsb_v();
  }
};

// Which sliding-window amplitude estimator the decoder uses. Auto picks the
// most accurate one for the skin (golden::resolve_variant): joint LS
// demixing when carriers are off bin centres and the fit is well posed,
// else the exact sliding DFT (which equals LS for bin-centred carriers).
enum class DftVariant { Auto, Direct, Recursive, Damped, Exact, LsDemix };

struct DecoderConfig {
  int window = 32;             // N, samples in the sliding window
  DftVariant variant = DftVariant::Auto;
  double damping = 0.9999;     // r of the damped sliding DFT
  bool hann = false;           // Hann window instead of rectangular
  int hop = 1;                 // emit a frame every `hop` samples
  double ghost_threshold = 0.05;  // ghost filter: release below this g
  double ghost_onset = 0.05;      // ghost filter: new site above this rise
};

// Carriers on DFT bin centres k*fs/N (no leakage with a rectangular window),
// spread over the usable band, n of them. Throws ConfigError if n > N/2 - 1.
std::vector<double> plan_carriers(int n, double fs_hz, int window);

// Throws ConfigError naming the first offending field. `prefix` is prepended
// to field names (e.g. "skin").
void validate(const SkinConfig& skin, const std::string& prefix = "skin");
void validate(const DecoderConfig& dec, const SkinConfig& skin,
              const std::string& prefix = "decoder");

const char* to_string(DftVariant v);
DftVariant dft_variant_from_string(const std::string& s);  // throws ConfigError

}  // namespace eskin
