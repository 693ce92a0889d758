// The `eskin simulate` report: what a run of a scene on the virtual board
// gave, next to the golden model and the scene's ground truth, as one
// self-contained HTML page (html_page.h).
#pragma once

#include <string>
#include <vector>

namespace eskin::report {

struct Series {  // one curve over time
  std::string label;
  std::vector<double> t_ms, value;
};

struct SpikeTrain {  // spikes of one model: time and taxel index
  std::string label;
  std::vector<double> t_ms;
  std::vector<int> taxel;
};

struct PressLatency {
  std::string taxel;           // "r0c1"
  double onset_ms = 0;         // truth: the press starts
  double fpga_us = -1;         // first FPGA frame on the host showing it lit (-1: none)
  double golden_us = -1;       // first golden frame showing it lit (-1: none)
};

struct SimulateReport {
  std::string title, scene_file, summary;
  std::vector<std::string> taxel_labels;     // row-major
  std::vector<std::string> carrier_labels;   // rows then columns
  // Heatmaps: taxel x time (FPGA packets, golden and truth at the same times).
  std::vector<double> frame_t_ms;
  std::vector<std::vector<double>> fpga_kpa, golden_kpa, truth_kpa;  // [taxel][frame]
  double kpa_max = 1;
  std::vector<Series> fpga_amp, golden_amp;  // per carrier, LSB peak
  std::vector<SpikeTrain> spikes;            // FPGA, golden
  std::vector<PressLatency> latency;
  std::vector<std::string> error_head;
  std::vector<std::vector<std::string>> error_rows;
  std::vector<std::vector<std::string>> run_rows;  // {figure, value}
};

void write_simulate_report(const SimulateReport& r, const std::string& path);

}  // namespace eskin::report
