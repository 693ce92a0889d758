// `eskin bench tradeoff`: the speed/accuracy map of the DTMF decoders. Each
// point is one decoder configuration, evaluated on the default scene's
// stimuli (scenes/neuroskin2.yaml) with its carrier plan; points are
// independent jobs (a local thread pool, or a Slurm job array).
//
// Axes (tradeoff_axes(): the table to extend; the Hall path's OSR/DIG_FILT
// and localisation table resolution go there when it exists):
//   variant   fpga-exact (host/engine: the FPGA's integers), fpga-goertzel
//             (hls/sdft_damped.h block Goertzel), golden-{direct, recursive,
//             damped, exact} (double), golden-ls (cross-talk removal on)
//   n         window length;  cw/tw/fb  word widths of the exact DFT
//   carriers  thesis (1.9..10 kHz, off the DFT bins) or bin (bin centres)
//   ghost     improved (the top's greedy pairing) / off / thesis (golden only)
//   step      samples per frame (taxels, neuron step);  decim  packets per frames
// Per point: latency (FPGA: the frame engine's clocks for the scene's
// slowest frame, from its instruction-set model, which `eskin bench
// latency` checks against Verilator; µs at the top's 18 MHz; delay =
// window centre + step wait + processing, ms; whether that frame fits in
// its step),  update rates, resources
// (Yosys synth_ice40 -dsp -spram -abc9 of the point's dtmf_top build with its
// microcode, cached; or the stored table), errors against ground truth and against the golden direct
// DFT (amplitude, % of a full carrier; pressure, kPa RMS), spikes against a
// reference neuron layer (double, one step per sample, on the true taxels).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace eskin::bench {

struct TradePoint {
  std::string variant = "fpga-exact";
  int n = 32, cw = 16, tw = 10, fb = 0;
  std::string carriers = "thesis";
  std::string ghost = "improved";
  int step = 35, decim = 1;
  std::string key() const;  // unique, canonical: the CSV's first columns
};

struct TradeRow {
  TradePoint p;
  // NaN / -1 where a figure does not apply (no RTL, no taxels, ...).
  double latency_cycles = -1, latency_us = -1, delay_ms = 0, update_hz = 0, packet_hz = 0;
  long luts = -1, dsp = -1, bram = -1, spram = -1;
  std::string resources;  // "synth", "table", or why not
  double amp_err_truth = 0, amp_err_golden = 0, pressure_err = -1, spike_err = -1;
  long spikes = -1, spikes_ref = -1;
  int pareto_latency = 0, pareto_resources = 0;
  int keeps_up = -1;  // FPGA: 1 when the slowest frame fits in its step (no frame lost)
};

// One axis of the sweep: the values of the full and of the quick sweep.
struct TradeAxis {
  std::string name;
  std::vector<std::string> full, quick;
};
const std::vector<TradeAxis>& tradeoff_axes();

// Grid over (variant, n, carriers) plus every other axis varied alone
// around the default point; points that cannot be built are left out.
std::vector<TradePoint> tradeoff_points(bool quick);

// Synthesis results keyed by the parameter set of the point's top build.
struct SynthEntry { long luts = -1, dsp = -1, bram = -1, spram = -1; };
using SynthTable = std::map<std::string, SynthEntry>;
SynthTable read_synth_table(const std::string& path);   // empty if absent
void write_synth_table(const std::string& path, const SynthTable& t);
// The parameter-set key of a point's top build ("" when it has none).
std::string synth_key(const TradePoint& p);
// Runs Yosys for the key's build (cached under cache_dir); throws on failure.
SynthEntry synthesize(const TradePoint& p, const std::string& cache_dir);

// Evaluates one point. table: stored results; synth_cache non-empty: run
// Yosys for builds the table lacks.
TradeRow evaluate_point(const TradePoint& p, const SynthTable& table,
                        const std::string& synth_cache);

// Marks the Pareto fronts (error vs delay, error vs LUTs).
void mark_pareto(std::vector<TradeRow>& rows);

std::string tradeoff_csv_header();
std::string tradeoff_csv_row(const TradeRow& r);
TradePoint parse_point(const std::string& csv_line);  // the key columns of a row / points file

void write_tradeoff_report(const std::string& path, const std::vector<TradeRow>& rows,
                           const std::string& title);

}  // namespace eskin::bench
