#include "host/report/simulate_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "host/report/html_page.h"

namespace eskin::report {
namespace {

const char* kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                          "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

nlohmann::json xy(const std::vector<double>& x, const std::vector<double>& y) {
  nlohmann::json pts = nlohmann::json::array();
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) pts.push_back({{"x", x[i]}, {"y", y[i]}});
  return pts;
}

nlohmann::json axes(const std::string& x, const std::string& y) {
  return {{"x", {{"type", "linear"}, {"title", {{"display", true}, {"text", x}}}}},
          {"y", {{"title", {{"display", true}, {"text", y}}}}}};
}

void amplitude_chart(Page& page, const SimulateReport& r) {
  nlohmann::json sets = nlohmann::json::array();
  for (size_t k = 0; k < r.fpga_amp.size(); ++k) {
    const char* c = kColours[k % 10];
    sets.push_back({{"label", r.fpga_amp[k].label}, {"data", xy(r.fpga_amp[k].t_ms, r.fpga_amp[k].value)},
                    {"borderColor", c}, {"pointRadius", 0}, {"borderWidth", 1.5}});
    if (k < r.golden_amp.size())
      sets.push_back({{"label", r.golden_amp[k].label},
                      {"data", xy(r.golden_amp[k].t_ms, r.golden_amp[k].value)},
                      {"borderColor", c}, {"borderDash", {4, 3}}, {"pointRadius", 0},
                      {"borderWidth", 1}});
  }
  page.chart({{"type", "line"},
              {"data", {{"datasets", sets}}},
              {"options", {{"parsing", false}, {"scales", axes("time (ms)", "carrier amplitude (LSB peak)")}}}},
             380);
}

void raster_chart(Page& page, const SimulateReport& r) {
  nlohmann::json sets = nlohmann::json::array();
  for (size_t s = 0; s < r.spikes.size(); ++s) {
    std::vector<double> y;
    for (int t : r.spikes[s].taxel) y.push_back(t + (s == 0 ? 0.15 : -0.15));  // side by side
    sets.push_back({{"label", r.spikes[s].label}, {"data", xy(r.spikes[s].t_ms, y)},
                    {"backgroundColor", kColours[s * 3 % 10]}, {"borderColor", kColours[s * 3 % 10]},
                    {"pointStyle", "line"}, {"rotation", 90}, {"pointRadius", 5},
                    {"borderWidth", 1.5}});
  }
  nlohmann::json sc = axes("time (ms)", "taxel (row-major index)");
  sc["y"]["min"] = -0.5;
  sc["y"]["max"] = double(r.taxel_labels.size()) - 0.5;
  page.chart({{"type", "scatter"}, {"data", {{"datasets", sets}}},
              {"options", {{"parsing", false}, {"scales", sc}}}},
             300);
}

void latency_chart(Page& page, const SimulateReport& r) {
  double hi = 0;
  for (const auto& l : r.latency) hi = std::max({hi, l.fpga_us, l.golden_us});
  const double bin = std::max(100.0, std::ceil(hi / 12 / 100) * 100);  // us, >= 12 bins
  const int n = int(hi / bin) + 1;
  std::vector<int> f(size_t(n), 0), g(size_t(n), 0);
  nlohmann::json labels = nlohmann::json::array();
  for (int i = 0; i < n; ++i) labels.push_back(fmt::format("{:.0f}-{:.0f}", i * bin, (i + 1) * bin));
  for (const auto& l : r.latency) {
    if (l.fpga_us >= 0) ++f[size_t(l.fpga_us / bin)];
    if (l.golden_us >= 0) ++g[size_t(l.golden_us / bin)];
  }
  page.chart({{"type", "bar"},
              {"data", {{"labels", labels},
                        {"datasets", {{{"label", "FPGA (virtual board, frame on the host)"}, {"data", f},
                                       {"backgroundColor", kColours[0]}},
                                      {{"label", "golden (decoded sample)"}, {"data", g},
                                       {"backgroundColor", kColours[1]}}}}}},
              {"options", {{"scales", {{"x", {{"title", {{"display", true}, {"text", "latency (us) from touch onset"}}}}},
                                       {"y", {{"title", {{"display", true}, {"text", "presses"}}}}}}}}}},
             260);
}

void heatmap(Page& page, const SimulateReport& r, const std::string& title,
             const std::vector<std::vector<double>>& v) {
  Heatmap h;
  h.title = title;
  h.row_labels = r.taxel_labels;
  h.x = r.frame_t_ms;
  h.values = v;
  h.vmax = std::ceil(r.kpa_max / 10) * 10;
  h.unit = "kPa";
  h.x_unit = "time (ms)";
  page.heatmap(h, int(std::max<size_t>(120, 18 * r.taxel_labels.size() + 40)));
}

}  // namespace

void write_simulate_report(const SimulateReport& r, const std::string& path) {
  Page page(r.title);
  page.text("Scene " + r.scene_file + ". " + r.summary);
  page.heading("Error summary against the scene's ground truth");
  page.table(r.error_head, r.error_rows);
  page.heading("Taxel pressure over time");
  heatmap(page, r, "FPGA (virtual board, taxel packets as received on the host)", r.fpga_kpa);
  heatmap(page, r, "Golden model (double precision, ghost-corrected)", r.golden_kpa);
  heatmap(page, r, "Ground truth", r.truth_kpa);
  page.heading("Carrier amplitudes over time");
  page.text("Solid: FPGA amplitude packets; dashed: golden model at the same samples.");
  amplitude_chart(page, r);
  page.heading("Spike raster");
  raster_chart(page, r);
  page.heading("Latency from touch onset to the first frame showing the taxel");
  page.text("FPGA: from the onset in the scene to the moment the last byte of the first taxel "
            "packet with the taxel lit reached the host through the virtual board's serial port "
            "(simulated time). Golden: to the newest sample of the first lit frame.");
  latency_chart(page, r);
  std::vector<std::vector<std::string>> rows;
  for (const auto& l : r.latency)
    rows.push_back({l.taxel, fmt::format("{:.3f}", l.onset_ms),
                    l.fpga_us >= 0 ? fmt::format("{:.1f}", l.fpga_us) : "none",
                    l.golden_us >= 0 ? fmt::format("{:.1f}", l.golden_us) : "none"});
  page.table({"taxel", "onset (ms)", "FPGA latency (us)", "golden latency (us)"}, rows);
  page.heading("Run");
  page.table({"figure", "value"}, r.run_rows);
  page.write(path);
}

}  // namespace eskin::report
