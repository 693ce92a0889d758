// Live view of a stream in the browser: an HTTP server (cpp-httplib) on
// 127.0.0.1 by default that serves one self-contained page (Chart.js from
// Debian's libjs-chart.js inlined, so it works offline) and its data:
//   GET /           the page: taxel heatmap, carrier amplitudes over time,
//                   spike raster, link statistics; it polls /data.json
//                   (GET /?static: the data at request time, no polling)
//   GET /data.json  {"taxels":{"t","rows","cols","values"[,"unit",
//                   "values_unit"]},"amplitudes":[{"t","amp":[..]}],
//                   "spikes":[{"t","neuron","layer"}],"status":{..},
//                   "link":{..},"carriers":[labels]}
//   GET /commands.json  the configuration commands the form offers
//                   (host/stream/commands.h: name, help, args)
//   POST /command   {"command":NAME,"args":[..]} to the command handler
//                   (ControlServer::handle), its JSON verdict back; 503
//                   without a handler, 400 on a body that is not JSON
// It is a Recorder: the stream's packets reach it like any other recorder.
#pragma once

#include <atomic>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "host/stream/recorder.h"

namespace httplib {
class Server;
}

namespace eskin::stream {

class LiveView : public Recorder {
 public:
  static constexpr size_t kAmplitudeHistory = 500;  // frames kept for the chart
  static constexpr size_t kSpikeHistory = 4000;     // spikes kept for the raster

  // Binds addr:port (port 0: any free port) and serves on its own thread.
  // Throws std::runtime_error when the address cannot be bound or the
  // chart library is missing (naming the file and its Debian package).
  LiveView(const std::string& addr, int port);
  ~LiveView() override;
  LiveView(const LiveView&) = delete;
  LiveView& operator=(const LiveView&) = delete;

  int port() const { return port_; }
  std::string url() const;
  // JSON object with link statistics, called on each /data.json request.
  void set_link_stats(std::function<std::string()> fn);
  // Carrier names for the amplitude chart, rows then columns ("row 0 ·
  // 1209 Hz"); without, "carrier K".
  void set_carrier_labels(std::vector<std::string> labels);
  // Taxel codes in a physical unit (e.g. kPa through the scene's
  // conductance curve); the heat map and its colour bar then show it.
  void set_taxel_unit(std::string unit, std::function<double(int64_t code)> to_unit);
  // Answers POST /command (a JSON request line -> a JSON reply line);
  // nullptr: none (503). Thread-safe; clear it before its target goes.
  void set_command_handler(std::function<std::string(const std::string&)> handler);

  // Sparse taxel frames are taken whole from the packet (an empty one
  // clears the map); when dense taxels of the same frame arrived first,
  // they are complete and the sparse packet adds nothing.
  void packet(const link::Packet& p) override;
  void write(const PacketKind& kind, const std::vector<Row>& rows) override;
  void flush() override {}

  std::string data_json() const;
  std::string page_html() const;

 private:
  struct AmpFrame {
    int64_t t;
    std::vector<int64_t> amp;
  };
  struct Spike {
    int64_t t, layer, neuron;
  };

  mutable std::mutex mu_;
  int64_t taxel_t_ = -1;
  bool taxel_dense_ = false;  // taxels_ came from a dense packet
  int rows_ = 0, cols_ = 0;
  std::vector<int64_t> taxels_;
  std::deque<AmpFrame> amps_;
  std::deque<Spike> spikes_;
  std::string status_json_ = "null";
  std::function<std::string()> link_stats_;
  std::vector<std::string> carrier_labels_;
  std::string taxel_unit_;
  std::function<double(int64_t)> to_unit_;
  std::function<std::string(const std::string&)> command_handler_;

  std::string chart_js_;
  std::string addr_;
  int port_ = 0;
  std::unique_ptr<httplib::Server> server_;
  std::atomic<bool> listen_returned_{false};
  std::thread thread_;
};

}  // namespace eskin::stream
