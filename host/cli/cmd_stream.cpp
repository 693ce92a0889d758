// eskin stream: read the FPGA link (serial device, the virtual board's pty,
// or TCP), print decoded packets as NDJSON, record CSV / HDF5, and serve a
// live view. Runs until --duration / --count or SIGINT/SIGTERM, or until the
// board hangs up (the virtual board's pty, at the end of its scene); a
// serial device or TCP link that drops is reported on stderr and reopened,
// and recordings stay intact. Bytes that decode to no packet (a wrong
// --baud) end the run with the rate that decodes named, exit code 5.
#include <atomic>
#include <chrono>
#include <csignal>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "cli/command.h"
#include "cli/link_options.h"
#include "eskin/exit_codes.h"
#include "host/stream/link_stream.h"
#include "host/stream/live_view.h"
#include "host/stream/record_hdf5.h"
#include "host/stream/recorder.h"
#include "sim/scene.h"

namespace {

using namespace eskin::stream;

std::atomic<bool> g_interrupted{false};
extern "C" void on_signal(int) { g_interrupted = true; }

struct StreamArgs {
  eskin::cli::LinkArgs link;
  std::string csv_dir, hdf5_file, live, scene_file;
  double duration_s = 0;
  uint64_t count = 0;
  bool quiet = false;
  int flush_ms = 500;
};

// "[ADDR:]PORT" -> (addr, port); addr defaults to loopback.
std::pair<std::string, int> parse_live(const std::string& s) {
  const size_t colon = s.rfind(':');
  const std::string addr = colon == std::string::npos ? "127.0.0.1" : s.substr(0, colon);
  const std::string port = colon == std::string::npos ? s : s.substr(colon + 1);
  char* end = nullptr;
  const long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end || p < 0 || p > 65535)
    throw std::runtime_error("--live '" + s + "': expected [ADDR:]PORT with PORT 0..65535");
  std::string a = addr;
  if (a.size() > 1 && a.front() == '[' && a.back() == ']') a = a.substr(1, a.size() - 2);
  return {a, int(p)};
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// The run's configuration, stored as HDF5 root attributes.
std::map<std::string, std::string> run_attributes(const StreamArgs& a, const Endpoint& ep) {
  std::map<std::string, std::string> m{{"eskin_format", "eskin stream recording 1"},
                                       {"endpoint", ep.describe()},
                                       {"started_utc", utc_now()}};
  if (ep.kind == Endpoint::Kind::Serial) m["baud"] = std::to_string(ep.baud);
  if (a.scene_file.empty()) return m;
  const auto sc = eskin::sim::load_scene(a.scene_file);
  std::ifstream f(a.scene_file);
  std::ostringstream yaml;
  yaml << f.rdbuf();
  m["scene_file"] = a.scene_file;
  m["scene_yaml"] = yaml.str();
  m["scene_name"] = sc.name;
  m["skin_rows"] = std::to_string(sc.skin.rows);
  m["skin_cols"] = std::to_string(sc.skin.cols);
  m["adc_rate_hz"] = std::to_string(sc.skin.adc.rate_hz);
  m["adc_bits"] = std::to_string(sc.skin.adc.bits);
  std::string carriers;
  for (double f_hz : sc.skin.carrier_freqs_hz())
    carriers += (carriers.empty() ? "" : ",") + std::to_string(f_hz);
  m["carriers_hz"] = carriers;
  m["window"] = std::to_string(sc.decoder.window);
  return m;
}

void print_event(const LinkEvent& e) {
  switch (e.kind) {
    case LinkEvent::Kind::Opened:
      std::cerr << "eskin stream: link open: " << e.message << "\n";
      break;
    case LinkEvent::Kind::Lost:
      std::cerr << "eskin stream: link lost: " << e.message << "; reopening\n";
      break;
    case LinkEvent::Kind::OpenFailed:  // 1, 2, 4, 8, ...: no flood while unplugged
      if ((e.attempt & (e.attempt - 1)) == 0)
        std::cerr << "eskin stream: " << e.message << " (attempt " << e.attempt
                  << "; retrying)\n";
      break;
    case LinkEvent::Kind::HungUp:
      std::cerr << "eskin stream: " << e.message << "; the stream ends\n";
      break;
    case LinkEvent::Kind::Idle:
    case LinkEvent::Kind::Resumed:
      std::cerr << "eskin stream: " << e.message << "\n";
      break;
    case LinkEvent::Kind::WrongBaud:
      std::cerr << "eskin stream: error: " << e.message << "\n";
      break;
  }
}

int run_stream(const StreamArgs& a) {
  const Endpoint ep = a.link.endpoint();
  RecorderSet recorders;
  if (!a.quiet) recorders.add(std::make_unique<NdjsonRecorder>(std::cout));
  if (!a.csv_dir.empty()) recorders.add(std::make_unique<CsvRecorder>(a.csv_dir));
  if (!a.hdf5_file.empty())
    recorders.add(std::make_unique<Hdf5Recorder>(a.hdf5_file, run_attributes(a, ep)));
  std::unique_ptr<LiveView> live;
  StreamOptions opt;
  opt.endpoint = ep;
  opt.queue_capacity = 0;  // callbacks only
  LinkStream stream(opt);
  if (!a.live.empty()) {
    const auto [addr, port] = parse_live(a.live);
    live = std::make_unique<LiveView>(addr, port);
    live->set_link_stats([&stream] { return stats_json(stream.stats()); });
    recorders.add(live.get());
    std::cerr << "eskin stream: live view at " << live->url() << "\n";
  }

  std::mutex rec_mu;
  std::atomic<uint64_t> packets{0};
  std::string record_error;  // a recorder failed (disk full, ...): stop the run
  stream.on_packet([&](const eskin::link::Packet& p) {
    std::lock_guard<std::mutex> lk(rec_mu);
    if ((a.count && packets >= a.count) || !record_error.empty()) return;
    try {
      recorders.write(p);
    } catch (const std::exception& e) {
      record_error = e.what();
    }
    ++packets;
  });
  stream.on_event(print_event);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  stream.start();

  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto last_flush = t0;
  while (!g_interrupted && stream.ended() == StreamEnd::Running) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const auto now = clock::now();
    if (a.count && packets >= a.count) break;
    {
      std::lock_guard<std::mutex> lk(rec_mu);
      if (!record_error.empty()) throw std::runtime_error(record_error);
    }
    if (a.duration_s > 0 && now - t0 >= std::chrono::duration<double>(a.duration_s)) break;
    if (now - last_flush >= std::chrono::milliseconds(a.flush_ms)) {
      std::lock_guard<std::mutex> lk(rec_mu);
      recorders.flush();
      last_flush = now;
    }
  }
  stream.stop();
  {
    std::lock_guard<std::mutex> lk(rec_mu);
    recorders.flush();
  }
  const StreamStats st = stream.stats();
  std::cerr << "eskin stream: " << packets << " packets; link " << stats_json(st) << "\n";
  if (st.connects == 0) {
    std::cerr << "eskin stream: error: the link never opened (" << ep.describe() << ")\n";
    return 1;
  }
  // A wrong baud rate (print_event said which rate decodes), or a run too
  // short to find out: bytes and link errors but not one packet.
  if (stream.ended() == StreamEnd::WrongBaud) return eskin::exit_code(eskin::Exit::no_packets);
  if (st.link.frames_ok == 0 && st.corrupt() > 0) {
    std::cerr << "eskin stream: error: " << st.link.bytes << " bytes with " << st.corrupt()
              << " link errors and no packet decoded (" << ep.describe()
              << "): is --baud the board's rate?\n";
    return eskin::exit_code(eskin::Exit::no_packets);
  }
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<StreamArgs>();
  auto* sub = app.add_subcommand(
      "stream", "read the FPGA link: NDJSON to stdout, CSV/HDF5 recording, live view");
  a->link.add_to(sub);
  sub->add_option("--csv", a->csv_dir, "record DIR/<table>.csv (amplitudes, taxels, spikes, status; hall_* for a Hall board)");
  sub->add_option("--hdf5", a->hdf5_file, "record one HDF5 file (flushed every --flush-ms)");
  sub->add_option("--live", a->live, "serve the live view on [ADDR:]PORT (ADDR default 127.0.0.1)");
  sub->add_option("--scene", a->scene_file, "scene file: its configuration goes into the HDF5 attributes")
      ->check(CLI::ExistingFile);
  sub->add_option("--duration", a->duration_s, "stop after S seconds (wall clock)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--count", a->count, "stop after N packets");
  sub->add_option("--flush-ms", a->flush_ms, "flush recordings every MS milliseconds")
      ->check(CLI::Range(10, 60000));
  sub->add_flag("--quiet,-q", a->quiet, "no NDJSON on stdout");
  return [a] { return run_stream(*a); };
}

ESKIN_COMMAND("stream", setup);

}  // namespace
