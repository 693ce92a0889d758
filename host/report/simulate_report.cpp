#include "host/report/simulate_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "host/report/html_page.h"
#include "host/report/report_style.h"

namespace eskin::report {
namespace {

const char* kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                          "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

nlohmann::json xy(const std::vector<double>& x, const std::vector<double>& y) {
  nlohmann::json pts = nlohmann::json::array();
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) pts.push_back({{"x", x[i]}, {"y", y[i]}});
  return pts;
}

std::string css(Rgb8 c) { return fmt::format("rgb({},{},{})", c.r, c.g, c.b); }

// Linear axes; x tight on [x_lo, x_hi] (the data's extent), its ticks
// Chart.js's round ones inside it, not the bounds themselves.
nlohmann::json axes(const std::string& x, const std::string& y, double x_lo, double x_hi) {
  nlohmann::json a = {{"x", {{"type", "linear"}, {"title", {{"display", true}, {"text", x}}}}},
                      {"y", {{"title", {{"display", true}, {"text", y}}}}}};
  if (x_hi > x_lo) {
    a["x"]["min"] = x_lo;
    a["x"]["max"] = x_hi;
    a["x"]["ticks"]["includeBounds"] = false;
  }
  return a;
}

// One panel per carrier (small multiples), titled by its row or column and
// frequency: the FPGA's amplitude on the left axis and FPGA - golden at the
// same samples on the right axis (the two agree to a fraction of an LSB, so
// drawn on one axis the golden line would hide under the FPGA's).
void amplitude_panels(Page& page, const SimulateReport& r) {
  std::vector<nlohmann::json> panels;
  for (size_t k = 0; k < r.fpga_amp.size(); ++k) {
    const Series& f = r.fpga_amp[k];
    std::map<double, double> fpga_at;
    for (size_t i = 0; i < f.t_ms.size(); ++i) fpga_at[f.t_ms[i]] = f.value[i];
    std::vector<double> dt, dv;
    if (k < r.golden_amp.size())
      for (size_t i = 0; i < r.golden_amp[k].t_ms.size(); ++i) {
        const auto it = fpga_at.find(r.golden_amp[k].t_ms[i]);
        if (it == fpga_at.end()) continue;
        dt.push_back(it->first);
        dv.push_back(it->second - r.golden_amp[k].value[i]);
      }
    nlohmann::json sc = axes("time (ms)", "amplitude (LSB peak)", f.t_ms.empty() ? 0 : f.t_ms.front(),
                             f.t_ms.empty() ? 0 : f.t_ms.back());
    sc["y"]["ticks"]["color"] = css(kFpgaRgb);
    sc["y2"] = {{"position", "right"},
                {"title", {{"display", true}, {"text", "FPGA - golden (LSB)"}}},
                {"ticks", {{"color", css(kDiffRgb)}}},
                {"grid", {{"drawOnChartArea", false}}}};
    const std::string label = k < r.carrier_labels.size() ? r.carrier_labels[k] : f.label;
    panels.push_back(
        {{"type", "line"},
         {"data",
          {{"datasets",
            {{{"label", "FPGA"}, {"data", xy(f.t_ms, f.value)}, {"borderColor", css(kFpgaRgb)},
              {"backgroundColor", css(kFpgaRgb)}, {"pointRadius", 0}, {"borderWidth", 2},
              {"yAxisID", "y"}},
             {{"label", "FPGA - golden"}, {"data", xy(dt, dv)}, {"borderColor", css(kDiffRgb)},
              {"backgroundColor", css(kDiffRgb)}, {"pointRadius", 0}, {"borderWidth", 2},
              {"yAxisID", "y2"}}}}}},
         {"options",
          {{"parsing", false},
           {"scales", sc},
           {"plugins", {{"title", {{"display", true}, {"text", label}}},
                        {"legend", {{"labels", {{"boxWidth", 12}}}}}}}}}});
  }
  page.chart_grid(panels, kPanelColumns, kPanelHeightPx);
}

void raster_chart(Page& page, const SimulateReport& r) {
  nlohmann::json sets = nlohmann::json::array();
  double t_hi = 0;
  for (size_t s = 0; s < r.spikes.size(); ++s) {
    std::vector<double> y;
    for (int t : r.spikes[s].taxel) y.push_back(t + (s == 0 ? 0.15 : -0.15));  // side by side
    for (double t : r.spikes[s].t_ms) t_hi = std::max(t_hi, t);
    sets.push_back({{"label", r.spikes[s].label}, {"data", xy(r.spikes[s].t_ms, y)},
                    {"backgroundColor", kColours[s * 3 % 10]}, {"borderColor", kColours[s * 3 % 10]},
                    {"pointStyle", "line"}, {"rotation", 90}, {"pointRadius", 5},
                    {"borderWidth", 1.5}});
  }
  // Time from 0 to the last frame; one row per taxel, ticks on the taxels.
  // The bounds leave half a row for the markers; they are not a whole
  // number of steps apart, or Chart.js would start its ticks at the bound
  // (-0.5, 0.5, ...) instead of at the integers.
  nlohmann::json sc = axes("time (ms)", "taxel (row-major index)", 0,
                           r.frame_t_ms.empty() ? t_hi : r.frame_t_ms.back());
  sc["y"]["min"] = -0.55;
  sc["y"]["max"] = double(r.taxel_labels.size()) - 0.45;
  sc["y"]["ticks"] = {{"stepSize", 1}, {"includeBounds", false}};
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
  page.text("One panel per carrier: the FPGA's amplitude packets (left axis) and the FPGA's "
            "amplitude minus the golden model's at the same samples (right axis).");
  amplitude_panels(page, r);
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
