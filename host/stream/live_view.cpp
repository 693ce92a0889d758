#include "host/stream/live_view.h"

#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "host/stream/commands.h"
#include "host/stream/live_view_page.h"

#ifndef ESKIN_CHARTJS
#error "ESKIN_CHARTJS: path of Debian's chart.min.js (libjs-chart.js), set by host/CMakeLists.txt"
#endif

namespace eskin::stream {

namespace {

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return {};
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string json_array(const std::vector<int64_t>& v) {
  std::string s = "[";
  for (size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + std::to_string(v[i]);
  return s + "]";
}

}  // namespace

LiveView::LiveView(const std::string& addr, int port)
    : chart_js_(read_file(ESKIN_CHARTJS)), addr_(addr), server_(std::make_unique<httplib::Server>()) {
  if (chart_js_.empty())
    throw std::runtime_error(std::string("--live: ") + ESKIN_CHARTJS +
                             ": missing (Debian package libjs-chart.js)");
  server_->Get("/", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(page_html(), "text/html; charset=utf-8");
  });
  server_->Get("/data.json", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(data_json(), "application/json");
  });
  server_->Get("/commands.json", [](const httplib::Request&, httplib::Response& res) {
    nlohmann::json list = nlohmann::json::array();
    for (const CommandSpec& c : command_specs()) {
      nlohmann::json args = nlohmann::json::array();
      for (const CommandArg& a : c.args) args.push_back(a.name);
      list.push_back({{"name", c.name}, {"help", c.help}, {"args", args}});
    }
    res.set_content(list.dump(), "application/json");
  });
  server_->Post("/command", [this](const httplib::Request& req, httplib::Response& res) {
    std::function<std::string(const std::string&)> handler;
    {
      std::lock_guard<std::mutex> lk(mu_);
      handler = command_handler_;
    }
    if (!handler) {
      res.status = 503;
      res.set_content(nlohmann::json{{"ok", false},
                                     {"error", "this stream takes no commands (a TCP link, or "
                                               "it is ending)"}}.dump(),
                      "application/json");
      return;
    }
    if (!nlohmann::json::accept(req.body)) {
      res.status = 400;
      res.set_content(nlohmann::json{{"ok", false}, {"error", "the request body is not JSON"}}.dump(),
                      "application/json");
      return;
    }
    res.set_content(handler(req.body), "application/json");
  });
  port_ = port == 0 ? server_->bind_to_any_port(addr) : (server_->bind_to_port(addr, port) ? port : -1);
  if (port_ < 0)
    throw std::runtime_error("--live: cannot listen on " + addr + ":" + std::to_string(port));
  thread_ = std::thread([this] {
    server_->listen_after_bind();
    listen_returned_ = true;
  });
  // httplib's stop() does nothing until the listen loop runs: without this
  // wait a view destroyed at once would leave its thread in accept().
  while (!server_->is_running() && !listen_returned_)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

LiveView::~LiveView() {
  server_->stop();
  if (thread_.joinable()) thread_.join();
}

std::string LiveView::url() const {
  const bool v6 = addr_.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + addr_ + "]" : addr_) + ":" + std::to_string(port_) + "/";
}

void LiveView::set_link_stats(std::function<std::string()> fn) {
  std::lock_guard<std::mutex> lk(mu_);
  link_stats_ = std::move(fn);
}

void LiveView::set_carrier_labels(std::vector<std::string> labels) {
  std::lock_guard<std::mutex> lk(mu_);
  carrier_labels_ = std::move(labels);
}

void LiveView::set_taxel_unit(std::string unit, std::function<double(int64_t)> to_unit) {
  std::lock_guard<std::mutex> lk(mu_);
  taxel_unit_ = std::move(unit);
  to_unit_ = std::move(to_unit);
}

void LiveView::set_command_handler(std::function<std::string(const std::string&)> handler) {
  std::lock_guard<std::mutex> lk(mu_);
  command_handler_ = std::move(handler);
}

void LiveView::packet(const link::Packet& p) {
  if (p.type != link::kTaxelsSparse) return;
  std::lock_guard<std::mutex> lk(mu_);
  if (taxel_dense_ && int64_t(p.t) == taxel_t_) return;
  // The grid is the dense packets' size, grown to the sparse entries' reach.
  int rows = rows_, cols = cols_;
  for (const link::SparseTaxel& s : p.sparse) {
    rows = std::max(rows, s.row + 1);
    cols = std::max(cols, s.col + 1);
  }
  taxels_.assign(size_t(rows) * size_t(cols), 0);
  rows_ = rows, cols_ = cols;
  for (const link::SparseTaxel& s : p.sparse) taxels_[size_t(s.row) * size_t(cols) + s.col] = s.value;
  taxel_t_ = p.t;
  taxel_dense_ = false;
}

void LiveView::write(const PacketKind& kind, const std::vector<Row>& rows) {
  std::lock_guard<std::mutex> lk(mu_);
  const std::string table = kind.table;
  for (const Row& r : rows) {
    const int64_t t = r.scalars.size() > 1 ? r.scalars[1] : 0;
    if (table == "taxels" && r.scalars.size() >= 4) {
      taxel_t_ = t;
      taxel_dense_ = true;
      rows_ = int(r.scalars[2]);
      cols_ = int(r.scalars[3]);
      taxels_ = r.values;
    } else if (table == "amplitudes") {
      amps_.push_back({t, r.values});
      if (amps_.size() > kAmplitudeHistory) amps_.pop_front();
    } else if (table == "spikes" && r.scalars.size() >= 4) {
      spikes_.push_back({t, r.scalars[2], r.scalars[3]});
      if (spikes_.size() > kSpikeHistory) spikes_.pop_front();
    } else if (table == "status") {
      status_json_ = ndjson_line(kind, r);
    }
  }
}

std::string LiveView::data_json() const {
  std::lock_guard<std::mutex> lk(mu_);
  std::string s = "{\"taxels\":{\"t\":" + std::to_string(taxel_t_) +
                  ",\"rows\":" + std::to_string(rows_) + ",\"cols\":" + std::to_string(cols_) +
                  ",\"values\":" + json_array(taxels_);
  if (to_unit_) {
    nlohmann::json v = nlohmann::json::array();
    for (int64_t code : taxels_) v.push_back(to_unit_(code));
    s += ",\"unit\":" + nlohmann::json(taxel_unit_).dump() + ",\"values_unit\":" + v.dump();
  }
  s += "},\"amplitudes\":[";
  for (size_t i = 0; i < amps_.size(); ++i)
    s += std::string(i ? "," : "") + "{\"t\":" + std::to_string(amps_[i].t) +
         ",\"amp\":" + json_array(amps_[i].amp) + "}";
  s += "],\"spikes\":[";
  for (size_t i = 0; i < spikes_.size(); ++i)
    s += std::string(i ? "," : "") + "{\"t\":" + std::to_string(spikes_[i].t) +
         ",\"layer\":" + std::to_string(spikes_[i].layer) +
         ",\"neuron\":" + std::to_string(spikes_[i].neuron) + "}";
  s += "],\"status\":" + status_json_;
  s += ",\"link\":" + (link_stats_ ? link_stats_() : std::string("null"));
  s += ",\"carriers\":" + nlohmann::json(carrier_labels_).dump() + "}";
  return s;
}

std::string LiveView::page_html() const {
  std::string page = kLiveViewPage;
  const auto put = [&](const std::string& key, const std::string& value) {
    const size_t at = page.find(key);
    if (at != std::string::npos) page.replace(at, key.size(), value);
  };
  put("/*INITIAL_DATA*/null", data_json());  // first paint needs no request
  put("/*CHART_JS*/", chart_js_);            // last: its text is not searched
  return page;
}

}  // namespace eskin::stream
