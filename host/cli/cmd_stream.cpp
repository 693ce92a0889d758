// eskin stream: read the FPGA link (serial device, the virtual board's pty,
// or TCP), print decoded packets as NDJSON, record CSV / HDF5, and serve a
// live view. Runs until --duration / --count, SIGINT/SIGTERM, the end of
// stdout's reader (`| head`), or until the board hangs up (the virtual
// board's pty, at the end of its scene); a serial device or TCP link that
// drops is reported on stderr and reopened, and recordings stay intact.
// Bytes that decode to no packet (a wrong --baud) end the run with the rate
// that decodes named, exit code 5. It owns the serial port (port_lock.h)
// and takes commands for the board while it records (control_server.h:
// `eskin config` on the same port goes through it).
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <mutex>
#include <sstream>
#include <thread>

#include "cli/command.h"
#include "cli/link_options.h"
#include "eskin/exit_codes.h"
#include "host/stream/control_server.h"
#include "host/stream/link_stream.h"
#include "host/stream/live_address.h"
#include "host/stream/live_view.h"
#include "host/stream/port_lock.h"
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
  bool quiet = false, force = false, live_public = false;
  int flush_ms = 500;
};

// A command's verdict on stderr, as `eskin config` prints it.
void print_verdict(const CommandOutcome& o) {
  std::string args;
  for (const std::string& x : o.args) args += " " + x;
  std::cerr << "eskin stream: command " << o.command << args;
  if (!o.error.empty()) {
    std::cerr << ": not sent: " << o.error << "\n";
    return;
  }
  std::cerr << " (type 0x" << std::hex << int(o.reply.type) << std::dec << ", seq "
            << int(o.reply.seq) << "): " << o.reply.message << "\n";
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
  check_new_recording(a.hdf5_file, a.csv_dir, a.force);
  LiveAddress live_at;
  if (!a.live.empty()) {
    live_at = parse_live_address(a.live);
    if (!live_at.loopback && !a.live_public)
      throw std::invalid_argument("--live " + a.live + ": " + live_at.addr +
                                  " is not a loopback address: anyone who reaches it sees the "
                                  "data and can send commands to the board; pass --live-public "
                                  "to serve it there anyway");
  }
  // One process owns a serial port (port_lock.h); a TCP link is the
  // bridge's to share.
  PortLock lock;
  std::optional<PortPaths> port;
  if (ep.kind == Endpoint::Kind::Serial) {
    port = port_paths(ep.path);
    PortHolder holder;
    if (!lock.try_acquire(*port, "eskin stream", true, &holder)) {
      std::cerr << "eskin stream: error: " << held_message(*port, holder) << "\n";
      return eskin::exit_code(eskin::Exit::port_held);
    }
  }
  // stdout's reader may leave (`eskin stream | head`): a write error ends the
  // run with the recordings flushed, not a silent death.
  std::signal(SIGPIPE, SIG_IGN);
  RecorderSet recorders;
  NdjsonRecorder* ndjson = nullptr;
  if (!a.quiet) {
    auto r = std::make_unique<NdjsonRecorder>(std::cout);
    ndjson = r.get();
    recorders.add(std::move(r));
  }
  if (!a.csv_dir.empty()) recorders.add(std::make_unique<CsvRecorder>(a.csv_dir));
  if (!a.hdf5_file.empty())
    recorders.add(std::make_unique<Hdf5Recorder>(a.hdf5_file, run_attributes(a, ep)));
  std::unique_ptr<LiveView> live;
  StreamOptions opt;
  opt.endpoint = ep;
  opt.queue_capacity = 0;  // callbacks only
  LinkStream stream(opt);
  if (!a.live.empty()) {
    live = std::make_unique<LiveView>(live_at.addr, live_at.port);
    live->set_link_stats([&stream] { return stats_json(stream.stats()); });
    if (!a.scene_file.empty()) {  // carriers by frequency, taxels in kPa
      const auto sc = eskin::sim::load_scene(a.scene_file);
      live->set_carrier_labels(sc.skin.carrier_labels());
      live->set_taxel_unit("kPa", [skin = sc.skin](int64_t code) {
        return skin.conductance.inverse(double(code) / 32768.0);  // UQ1.15 taxel
      });
    }
    recorders.add(live.get());
    // One write: a reader waiting for the URL sees the whole line and its warning at once.
    std::ostringstream note;
    note << "eskin stream: live view at " << live->url() << "\n";
    if (!live_at.loopback)
      note << "eskin stream: warning: the live view is served on " << live_at.addr
           << ", not only this machine: anyone who reaches port " << live->port()
           << " sees the data and can send commands to the board\n";
    std::cerr << note.str() << std::flush;
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
  // Commands while it records: `eskin config` on the same port finds the
  // socket through the port's record; each verdict goes on stderr and into
  // the recordings, in the order they came.
  std::unique_ptr<ControlServer> control;
  if (port) {
    control = std::make_unique<ControlServer>(stream, port->socket, [&](const CommandOutcome& o) {
      print_verdict(o);
      std::lock_guard<std::mutex> lk(rec_mu);
      try {
        recorders.command(command_record(o));
      } catch (const std::exception& e) {
        if (record_error.empty()) record_error = e.what();
      }
    });
    std::cerr << "eskin stream: taking commands (eskin config --port " << ep.path << " ...) on "
              << control->path() << "\n";
    if (live)  // the page's command form: the same requests, the same records
      live->set_command_handler([c = control.get()](const std::string& req) { return c->handle(req); });
  }

  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto last_flush = t0;
  int stdout_error = 0;  // stdout's write failed (EPIPE: its reader left)
  while (!g_interrupted && stream.ended() == StreamEnd::Running) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const auto now = clock::now();
    if (a.count && packets >= a.count) break;
    {
      std::lock_guard<std::mutex> lk(rec_mu);
      if (!record_error.empty()) throw std::runtime_error(record_error);
      if (ndjson && ndjson->failed()) {
        stdout_error = ndjson->error();
        break;
      }
    }
    if (a.duration_s > 0 && now - t0 >= std::chrono::duration<double>(a.duration_s)) break;
    if (now - last_flush >= std::chrono::milliseconds(a.flush_ms)) {
      std::lock_guard<std::mutex> lk(rec_mu);
      recorders.flush();
      last_flush = now;
    }
  }
  if (live) live->set_command_handler(nullptr);
  control.reset();  // no command after the last packet is recorded
  stream.stop();
  {
    std::lock_guard<std::mutex> lk(rec_mu);
    recorders.flush();
    if (!stdout_error && ndjson && ndjson->failed()) stdout_error = ndjson->error();
  }
  const StreamStats st = stream.stats();
  if (stdout_error == EPIPE)
    std::cerr << "eskin stream: stdout closed by its reader: NDJSON output stopped, recordings "
                 "flushed\n";
  std::cerr << "eskin stream: " << packets << " packets; link " << stats_json(st) << "\n";
  if (stdout_error && stdout_error != EPIPE) {
    std::cerr << "eskin stream: error: cannot write stdout: " << std::strerror(stdout_error)
              << "\n";
    return eskin::exit_code(eskin::Exit::failure);
  }
  if (st.connects == 0) {
    std::cerr << "eskin stream: error: the link never opened (" << ep.describe() << ")\n";
    return eskin::exit_code(eskin::Exit::failure);
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
  return eskin::exit_code(eskin::Exit::ok);
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<StreamArgs>();
  auto* sub = app.add_subcommand(
      "stream", "read the FPGA link: NDJSON to stdout, CSV/HDF5 recording, live view");
  a->link.add_to(sub);
  sub->add_option("--csv", a->csv_dir, "record DIR/<table>.csv (amplitudes, taxels, spikes, status; hall_* for a Hall board)");
  sub->add_option("--hdf5", a->hdf5_file, "record one HDF5 file (flushed every --flush-ms)");
  sub->add_flag("--force", a->force, "overwrite an existing --hdf5 file or --csv tables");
  sub->add_option("--live", a->live,
                  "serve the live view on [ADDR:]PORT (ADDR default 127.0.0.1; PORT 0: any)");
  sub->add_flag("--live-public", a->live_public,
                "allow --live on a non-loopback address (the view takes commands)");
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
