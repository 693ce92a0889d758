// eskin config: send one configuration command to the FPGA by name and
// report its verdict (accepted, or rejected with the decoded reason); the
// hall-* commands go to a Hall top and are judged by its HALL_DECODE_STATUS.
// Exit codes: 0 accepted, 3 rejected, 4 no verdict (no STATUS came back),
// 6 the port is held by a process that takes no commands (another config).
// When `eskin stream` holds the serial port, the command goes through it
// (its control socket: host/stream/control_server.h) with the same output;
// otherwise config opens the port itself, holding it for the command.
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "cli/command.h"
#include "cli/link_options.h"
#include "eskin/exit_codes.h"
#include "host/stream/control_server.h"
#include "host/stream/link_stream.h"
#include "host/stream/port_lock.h"

namespace {

using namespace eskin::stream;

struct ConfigArgs {
  eskin::cli::LinkArgs link;
  std::string name;
  std::vector<std::string> args;
  int timeout_ms = 2000;
};

void print_status(const eskin::link::StatusBlock& s) {
  std::cout << "  status: accepted " << s.cmd_accepted << ", rejected " << s.cmd_rejected
            << ", cmd crc errors " << s.cmd_crc_errors << ", cmd frame errors "
            << s.cmd_frame_errors << ", cmd overflows " << s.cmd_overflows << ", output mask 0x"
            << std::hex << int(s.output_mask) << std::dec << ", dropped frames "
            << s.dropped_frames << ", frame overruns " << s.frame_overruns << ", spikes dropped "
            << s.spikes_dropped << ", adc overruns " << s.adc_overruns << ", uart rx errors "
            << s.uart_rx_errors << ", samples " << s.samples << "\n";
}

void print_hall_status(const eskin::link::HallDecodeStatus& s) {
  std::cout << "  hall decode status: accepted " << s.cmd_accepted << ", rejected "
            << s.cmd_rejected << ", cmd crc errors " << s.cmd_crc_errors << ", cmd frame errors "
            << s.cmd_frame_errors << ", cmd overflows " << s.cmd_overflows
            << ", baseline dropped " << s.baseline_dropped << ", ft skipped " << s.ft_skipped
            << "\n";
}

int report(const ConfigArgs& a, const CommandSpec* spec, const CommandReply& r) {
  std::cout << a.name << " (type 0x" << std::hex << int(r.type) << std::dec << ", seq "
            << int(r.seq) << "): " << r.message << "\n";
  if (r.ack != Ack::Pending && spec->hall) print_hall_status(r.hall_status);
  else if (r.ack != Ack::Pending) print_status(r.status);
  return ack_exit_code(r.ack);
}

// Through the stream that holds the port: its reply, or nothing when no
// stream listens on the socket (not up yet, or the holder is no stream).
// A request that went out without a reply is not sent again: the stream
// may have applied it.
std::optional<int> via_stream(const ConfigArgs& a, const CommandSpec* spec,
                              const PortPaths& port, const PortHolder& holder) {
  std::string line;
  try {
    // The stream waits up to --timeout-ms for the verdict: allow for that.
    line = control_request(port.socket, request_json(a.name, a.args, a.timeout_ms),
                           std::chrono::milliseconds(a.timeout_ms + 5000));
  } catch (const ControlUnreachable&) {
    return std::nullopt;
  } catch (const LinkError& e) {
    std::cerr << "eskin config: error: " << e.what() << " (sent through eskin stream, pid "
              << holder.pid << "; the command may have been applied: see its verdicts)\n";
    return eskin::exit_code(eskin::Exit::no_verdict);
  }
  std::cerr << "eskin config: sent through eskin stream (pid " << holder.pid << "), which holds "
            << port.port << "\n";
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (j.is_object() && j.value("ok", true) == false) {
    std::cerr << "eskin: error: " << j.value("error", line) << "\n";
    return j.value("exit", eskin::exit_code(eskin::Exit::failure));
  }
  return report(a, spec, reply_from_json(line));
}

int run_config(const ConfigArgs& a) {
  const CommandSpec* spec = find_command(a.name);
  if (!spec) {
    std::string known;
    for (const CommandSpec& c : command_specs()) known += std::string(" ") + c.name;
    throw std::invalid_argument("unknown command '" + a.name + "'; expected one of:" + known);
  }
  const std::vector<int64_t> values = parse_command_args(*spec, a.args);
  StreamOptions opt;
  opt.endpoint = a.link.endpoint();
  opt.reconnect = false;
  opt.queue_capacity = 0;
  PortLock lock;
  if (opt.endpoint.kind == Endpoint::Kind::Serial) {
    // A second reader of the tty would split its bytes with the holder:
    // go through the holding stream, or wait (up to the timeout) for a
    // holder that takes no commands (another config) to finish.
    const PortPaths port = port_paths(opt.endpoint.path);
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(a.timeout_ms);
    PortHolder holder;
    while (!lock.try_acquire(port, "eskin config", false, &holder)) {
      if (holder.serves_commands)
        if (const auto rc = via_stream(a, spec, port, holder)) return *rc;
      if (std::chrono::steady_clock::now() >= end) {
        std::cerr << "eskin config: error: " << held_message(port, holder) << "\n";
        return eskin::exit_code(eskin::Exit::port_held);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  LinkStream stream(opt);
  stream.start();
  const CommandReply r = stream.command(*spec, values, std::chrono::milliseconds(a.timeout_ms));
  stream.stop();
  return report(a, spec, r);
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<ConfigArgs>();
  std::string names;
  for (const CommandSpec& c : command_specs()) {
    names += std::string("\n  ") + c.name;
    for (const CommandArg& arg : c.args) names += std::string(" ") + arg.name;
    names += std::string(": ") + c.help;
  }
  auto* sub = app.add_subcommand(
      "config", "send a configuration command to the FPGA and report its verdict; commands:" + names);
  a->link.add_to(sub);
  sub->add_option("--timeout-ms", a->timeout_ms, "how long to wait for the verdict")
      ->check(CLI::Range(10, 60000));
  sub->add_option("command", a->name, "command name (see above)")->required();
  sub->add_option("args", a->args, "its arguments (decimal or 0x hex)");
  return [a] { return run_config(*a); };
}

ESKIN_COMMAND("config", setup);

}  // namespace
