// A small builder of self-contained HTML pages: headings, text, tables,
// Chart.js charts and canvas heatmaps. The chart library comes from
// Debian's libjs-chart.js and is inlined into the page, so the file opens
// anywhere, offline, with no external script or style.
//
//   eskin::report::Page page("Run report");
//   page.heading("Amplitudes");
//   page.chart({{"type", "line"}, {"data", ...}, {"options", ...}});  // Chart.js 3 config
//   page.heatmap({"taxel pressure", rows_labels, x_labels, values, 0, 60, "kPa"});
//   page.write("report.html");
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace eskin::report {

// values[r][c]: row r of the map (drawn top to bottom), column c (left to
// right); colour from vmin (dark blue) to vmax (red).
struct Heatmap {
  std::string title;
  std::vector<std::string> row_labels;
  std::vector<double> x;              // one per column, shown on the x axis
  std::vector<std::vector<double>> values;
  double vmin = 0, vmax = 1;
  std::string unit, x_unit;
};

// Round tick values for an axis from lo to hi: steps of 1, 2 or 5 x 10^k,
// the smallest that gives at most max_ticks ticks, each in [lo, hi].
std::vector<double> round_ticks(double lo, double hi, int max_ticks);

class Page {
 public:
  explicit Page(std::string title);
  void heading(const std::string& text);
  void text(const std::string& text);  // one paragraph, escaped
  void table(const std::vector<std::string>& head,
             const std::vector<std::vector<std::string>>& rows);
  // A Chart.js 3.9 chart; `config` is its {type, data, options} object.
  void chart(const nlohmann::json& config, int height_px = 320);
  void heatmap(const Heatmap& h, int height_px = 240);
  // Small multiples: one Chart.js chart per config, `columns` to a row,
  // each in a framed panel (report_style.h) of height_px.
  void chart_grid(const std::vector<nlohmann::json>& configs, int columns, int height_px);

  std::string html() const;
  void write(const std::string& path) const;  // throws std::runtime_error naming the path

 private:
  std::string title_, body_;
  int next_id_ = 0;
  bool charts_ = false, heatmaps_ = false;
};

// HTML-escaped text.
std::string escape(const std::string& s);

}  // namespace eskin::report
