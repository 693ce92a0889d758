#include "host/report/html_page.h"

#include "host/report/report_style.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifndef ESKIN_CHARTJS
#error "ESKIN_CHARTJS: path of Debian's chart.min.js (libjs-chart.js)"
#endif

namespace eskin::report {
namespace {

std::string read_file(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(std::string("report: cannot read ") + what + " " + path +
                             " (install libjs-chart.js: scripts/bootstrap.sh)");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// JSON inside <script>: "</" would end the element.
std::string script_json(const nlohmann::json& j) {
  std::string s = j.dump();
  for (size_t at = 0; (at = s.find("</", at)) != std::string::npos; at += 3) s.replace(at, 2, "<\\/");
  return s;
}

// Draws every <canvas class="heatmap"> from its data-map JSON: one cell per
// value, a blue-to-red ramp, labels and a colour bar.
const char* kHeatmapJs = R"JS(
function eskinRamp(f) {
  f = Math.max(0, Math.min(1, f));
  const stops = [[19, 41, 120], [44, 123, 182], [171, 217, 233], [255, 255, 191],
                 [253, 174, 97], [215, 25, 28]];
  const x = f * (stops.length - 1), i = Math.min(stops.length - 2, Math.floor(x)), t = x - i;
  const c = stops[i].map((v, k) => Math.round(v + t * (stops[i + 1][k] - v)));
  return 'rgb(' + c.join(',') + ')';
}
function eskinHeatmap(canvas) {
  const m = JSON.parse(canvas.dataset.map), ctx = canvas.getContext('2d');
  const W = canvas.width = canvas.clientWidth, H = canvas.height = canvas.clientHeight;
  const left = 70, right = 70, top = 8, bottom = 28, rows = m.values.length;
  const cols = rows ? m.values[0].length : 0, pw = W - left - right, ph = H - top - bottom;
  ctx.font = '11px sans-serif';
  for (let r = 0; r < rows; ++r) {
    const y0 = top + r * ph / rows, y1 = top + (r + 1) * ph / rows;
    for (let c = 0; c < cols; ++c) {
      ctx.fillStyle = eskinRamp((m.values[r][c] - m.vmin) / (m.vmax - m.vmin));
      ctx.fillRect(left + c * pw / cols, y0, pw / cols + 0.5, y1 - y0 + 0.5);
    }
    ctx.fillStyle = '#222';
    ctx.textAlign = 'right';
    ctx.fillText(m.row_labels[r] || '', left - 6, (y0 + y1) / 2 + 4);
  }
  ctx.textAlign = 'center';
  for (const t of m.x_ticks) {  // round times (html_page.cpp, round_ticks), at their place
    const x = left + t.at * pw / cols;
    ctx.fillRect(x - 0.5, top + ph, 1, 4);
    ctx.fillText(t.label, x, H - 12);
  }
  ctx.fillText(m.x_unit, left + pw / 2, H - 1);
  for (let k = 0; k < ph; ++k) {
    ctx.fillStyle = eskinRamp(1 - k / ph);
    ctx.fillRect(W - right + 12, top + k, 14, 1);
  }
  ctx.fillStyle = '#222';
  ctx.textAlign = 'left';
  ctx.fillText(m.vmax + ' ' + m.unit, W - right + 30, top + 10);
  ctx.fillText(m.vmin + ' ' + m.unit, W - right + 30, top + ph);
}
document.querySelectorAll('canvas.heatmap').forEach(eskinHeatmap);
)JS";

}  // namespace

std::vector<double> round_ticks(double lo, double hi, int max_ticks) {
  if (!(hi > lo) || max_ticks < 2) return {lo};
  // step = m x 10^e, m in {1, 2, 5}; a tick k x step is computed as
  // (k m) x 10^e or (k m) / 10^-e, so 0.5 comes out as 0.5, not 0.5000000001.
  int e = int(std::floor(std::log10((hi - lo) / max_ticks)));
  const int ms[] = {1, 2, 5};
  const auto value = [&](double km) { return e >= 0 ? km * std::pow(10.0, e) : km / std::pow(10.0, -e); };
  for (int i = 0;; ++i) {
    const int m = ms[i % 3];
    if (i > 0 && i % 3 == 0) ++e;
    const double step = value(m);
    const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor(hi / step + 1e-9);
    if (k1 - k0 + 1 > max_ticks) continue;
    std::vector<double> t;
    for (double k = k0; k <= k1; k += 1) t.push_back(k == 0 ? 0.0 : value(k * m));
    return t;
  }
}

std::string escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

Page::Page(std::string title) : title_(std::move(title)) {}

void Page::heading(const std::string& text) { body_ += "<h2>" + escape(text) + "</h2>\n"; }

void Page::text(const std::string& text) { body_ += "<p>" + escape(text) + "</p>\n"; }

void Page::table(const std::vector<std::string>& head,
                 const std::vector<std::vector<std::string>>& rows) {
  body_ += "<table><tr>";
  for (const auto& h : head) body_ += "<th>" + escape(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& r : rows) {
    body_ += "<tr>";
    for (const auto& c : r) body_ += "<td>" + escape(c) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

void Page::chart(const nlohmann::json& config, int height_px) {
  const std::string id = "chart" + std::to_string(next_id_++);
  nlohmann::json cfg = config;
  cfg["options"]["maintainAspectRatio"] = false;
  cfg["options"]["animation"] = false;
  body_ += "<div class=\"chart\" style=\"height:" + std::to_string(height_px) +
           "px\"><canvas id=\"" + id + "\"></canvas></div>\n<script>new Chart(document.getElementById('" +
           id + "'), " + script_json(cfg) + ");</script>\n";
  charts_ = true;
}

void Page::heatmap(const Heatmap& h, int height_px) {
  // Ticks at round x values, placed by interpolation between the cells'
  // x (cell centres at column + 0.5).
  nlohmann::json ticks = nlohmann::json::array();
  if (h.x.size() >= 2)
    for (double t : round_ticks(h.x.front(), h.x.back(), 6)) {
      size_t i = 0;
      while (i + 2 < h.x.size() && h.x[i + 1] < t) ++i;
      const double at = double(i) + (t - h.x[i]) / (h.x[i + 1] - h.x[i]) + 0.5;
      char label[32];
      std::snprintf(label, sizeof label, "%g", t);
      ticks.push_back({{"at", at}, {"label", label}});
    }
  const nlohmann::json m = {{"row_labels", h.row_labels}, {"x", h.x},       {"values", h.values},
                            {"vmin", h.vmin},             {"vmax", h.vmax}, {"unit", h.unit},
                            {"x_unit", h.x_unit},         {"x_ticks", ticks}};
  if (!h.title.empty()) body_ += "<h3>" + escape(h.title) + "</h3>\n";
  body_ += "<canvas class=\"heatmap\" style=\"width:100%;height:" + std::to_string(height_px) +
           "px\" data-map=\"" + escape(m.dump()) + "\"></canvas>\n";
  heatmaps_ = true;
}

void Page::chart_grid(const std::vector<nlohmann::json>& configs, int columns, int height_px) {
  char border[64];
  std::snprintf(border, sizeof border, "%dpx solid rgb(%d,%d,%d)", kPanelBorderPx, kPanelBorder.r,
                kPanelBorder.g, kPanelBorder.b);
  body_ += "<div style=\"display:grid;grid-template-columns:repeat(" + std::to_string(columns) +
           ",1fr);gap:8px;margin:.5em 0\">\n";
  for (const nlohmann::json& config : configs) {
    const std::string id = "chart" + std::to_string(next_id_++);
    nlohmann::json cfg = config;
    cfg["options"]["maintainAspectRatio"] = false;
    cfg["options"]["animation"] = false;
    body_ += "<div class=\"chart\" style=\"height:" + std::to_string(height_px) + "px;border:" +
             border + "\"><canvas id=\"" + id + "\"></canvas></div>\n<script>new Chart(document.getElementById('" +
             id + "'), " + script_json(cfg) + ");</script>\n";
  }
  body_ += "</div>\n";
  charts_ = true;
}

std::string Page::html() const {
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
                  escape(title_) +
                  "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:1em auto;"
                  "padding:0 1em;color:#222}table{border-collapse:collapse;margin:.5em 0}"
                  "td,th{border:1px solid #bbb;padding:2px 8px;text-align:right}"
                  "th{background:#eee}.chart{position:relative;margin:.5em 0}</style>\n";
  if (charts_) h += "<script>\n" + read_file(ESKIN_CHARTJS, "Chart.js") + "\n</script>\n";
  h += "</head><body>\n<h1>" + escape(title_) + "</h1>\n" + body_;
  if (heatmaps_) h += "<script>" + std::string(kHeatmapJs) + "</script>\n";
  return h + "</body></html>\n";
}

void Page::write(const std::string& path) const {
  const std::string text = html();
  std::ofstream out(path, std::ios::binary);
  if (!out || !out.write(text.data(), std::streamsize(text.size())))
    throw std::runtime_error("report: cannot write " + path);
}

}  // namespace eskin::report
