// The scale table (docs/bitstream.md): for each FPGA target and sample
// rate, the largest square skin whose whole DTMF chain fits and meets
// timing, found by real Yosys + nextpnr runs (run_flow). Its rows are kept
// in docs/scale_table.csv, which `eskin bitstream` also reads to say which
// skins would fit when a build fails.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "host/fpga/flow.h"
#include "sim/scene.h"

namespace eskin::fpga {

// One FPGA of the table: a board, with its device override.
struct ScaleTarget {
  std::string label;   // "up5k", "ecp5-25k", "ecp5-85k"
  std::string board, device;
};
std::vector<ScaleTarget> scale_targets();
std::vector<double> scale_rates();  // 35 kS/s and 1 MS/s
std::vector<int> scale_sizes();     // n of the n x n skins tried, ascending

// The scene an n x n skin at fs gets: the base scene's analog chain, ADC
// bits and neuron, n rows and n columns of carriers on DFT bin centres
// (eskin::plan_carriers) in the shortest power-of-two window (>= 32) that
// holds them, sampled at fs.
sim::Scene scale_scene(const sim::Scene& base, int n, double fs);

// The frame engine a probe builds (FlowOptions::fast_shift, neuron_unit):
// its shifter, and where the neuron updates run.
struct EngineVariant {
  bool barrel = false;  // barrel shifter (else bit-serial)
  bool unit = false;    // the hardware neuron unit (else the microcode)
  bool lanes = false;   // with the unit: its lanes, which keep the state
  bool operator==(const EngineVariant& o) const {
    return barrel == o.barrel && unit == o.unit && lanes == o.lanes;
  }
};
std::string variant_name(EngineVariant v);  // "serial shifter, neuron unit"
// The option values of `eskin bitstream --engine-shifter` and `--neurons`
// for an engine (also the scale table's CSV fields): "serial" / "barrel",
// "engine" / "unit" / "lanes".
const char* shifter_name(EngineVariant v);
const char* neurons_name(EngineVariant v);

// After a build with `failed` missed timing at `failed_clk_hz` (0: no clock
// of `b` kept up with it at all): the smallest variant (bit-serial before
// barrel, microcode neurons before the unit: fewer logic cells first) whose
// core keeps up at a slower clock of `b` (choose_core_clock under
// `policy`), or none.
struct SlowerClock {
  EngineVariant engine;
  long clk_hz = 0;         // the board clock it keeps up at
  long engine_clocks = 0;  // its frame engine's clocks a frame (under the policy)
};
std::optional<SlowerClock> slower_clock_variant(const Board& b, const sim::Scene& scene,
                                                EngineVariant failed, long failed_clk_hz,
                                                LoadPolicy policy = LoadPolicy::Stress);

// For a failed DTMF build `r` of `scene` on `b` whose engine was the
// board's: when it missed timing (or no clock kept up) and another engine
// keeps up at a slower clock (under the build's load policy, r.policy), the
// options that build it, with that clock and the engine's clocks a frame;
// else "".
std::string slower_engine_hint(const Board& b, const sim::Scene& scene, const FlowReport& r);

// One probe: what run_flow reported for one target, rate, size and engine.
struct ScaleRow {
  std::string target, board, device;
  double sample_hz = 0;
  int rows = 0, cols = 0, window = 0, step = 0;
  long clk_hz = 0;
  long adc_clk_hz = 0;  // the ADC's own clock (FlowReport spec.adc_clk_hz), 0: clk_hz
  EngineVariant engine;
  bool fits = false, meets_timing = false;
  long logic_used = 0, logic_available = 0, dsp_used = 0, dsp_available = 0;
  long ram_used = 0, ram_available = 0, spram_used = 0;
  int seed = 1;  // the placer seed of the run reported (FlowReport::seed)
  double fmax_mhz = 0, seconds = 0;
  // The frame engine's clocks a frame (0: not recorded, rows from before
  // these columns): the frame's (budget), the measured worst case the clock
  // carries (FlowReport::engine_clocks) and its static bound (frame +
  // command, FlowReport::bound), which must stay within 90 % of the frame.
  long frame_clocks = 0, engine_clocks = 0, bound_clocks = 0;
  // The datapath the flow picked (choose_core_clock; CSV "engine" or
  // "streaming", datapath_name): with streaming the clocks above are the
  // control plane's and the chain's, the bound's limit 70 %.
  bool streaming = false;
  std::string failure;
  bool ok() const { return fits && meets_timing; }
};
ScaleRow scale_row(const ScaleTarget& t, const FlowReport& r);

// For every target and rate: a binary search over scale_sizes() (assuming
// that what does not fit at n does not fit above n either), one run_flow per
// probe into OUT/<target>/<rate>/<n>x<n>/ with the board's engine; when
// that misses timing, a second one with slower_clock_variant (if any) into
// OUT/<target>/<rate>/<n>x<n>-<shifter>-<neurons>/, and the size passes if
// either build does. `progress` sees every row.
// What to measure: empty lists mean all of scale_targets() (by label),
// scale_rates() and scale_sizes() (ascending).
struct ScaleSelection {
  std::vector<std::string> targets;
  std::vector<double> rates;
  std::vector<int> sizes;
};
std::vector<ScaleRow> run_scale_table(const sim::Scene& base, const FlowOptions& opt,
                                      ScaleSelection sel,
                                      const std::function<void(const ScaleRow&)>& progress);

// `old` without the rows of the targets and rates that `fresh` measured,
// then `fresh`: a partial run replaces only what it measured.
std::vector<ScaleRow> merge_scale_rows(const std::vector<ScaleRow>& old,
                                       const std::vector<ScaleRow>& fresh);

std::string scale_csv(const std::vector<ScaleRow>& rows);
std::vector<ScaleRow> parse_scale_csv(const std::string& text);  // throws naming the line
// The largest passing size per target and rate, as a Markdown table, with
// the smallest size no engine passed at and each engine's reason.
std::string scale_markdown(const std::vector<ScaleRow>& rows);

// "skins that fit ..." for a failed build of `board`/`device` at fs, from
// the table's rows (empty rows: says how to make the table).
std::string fit_hint(const std::vector<ScaleRow>& rows, const std::string& board,
                     const std::string& device, double fs);

}  // namespace eskin::fpga
