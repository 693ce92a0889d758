// The scale table (docs/bitstream.md): for each FPGA target and sample
// rate, the largest square skin whose whole DTMF chain fits and meets
// timing, found by real Yosys + nextpnr runs (run_flow). Its rows are kept
// in docs/scale_table.csv, which `eskin bitstream` also reads to say which
// skins would fit when a build fails.
#pragma once

#include <functional>
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

// One probe: what run_flow reported for one target, rate and size.
struct ScaleRow {
  std::string target, board, device;
  double sample_hz = 0;
  int rows = 0, cols = 0, window = 0, step = 0;
  long clk_hz = 0;
  bool fits = false, meets_timing = false;
  long logic_used = 0, logic_available = 0, dsp_used = 0, dsp_available = 0;
  long ram_used = 0, ram_available = 0, spram_used = 0;
  double fmax_mhz = 0, seconds = 0;
  std::string failure;
  bool ok() const { return fits && meets_timing; }
};
ScaleRow scale_row(const ScaleTarget& t, const FlowReport& r);

// For every target and rate: a binary search over scale_sizes() (assuming
// that what does not fit at n does not fit above n either), one run_flow per
// probe into OUT/<target>/<rate>/<n>x<n>/. `progress` sees every row.
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
// The largest passing size per target and rate, as a Markdown table.
std::string scale_markdown(const std::vector<ScaleRow>& rows);

// "skins that fit ..." for a failed build of `board`/`device` at fs, from
// the table's rows (empty rows: says how to make the table).
std::string fit_hint(const std::vector<ScaleRow>& rows, const std::string& board,
                     const std::string& device, double fs);

}  // namespace eskin::fpga
