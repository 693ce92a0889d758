// eskin config: send one configuration command to the FPGA by name and
// report its verdict (accepted, or rejected with the decoded reason); the
// hall-* commands go to a Hall top and are judged by its HALL_DECODE_STATUS.
// Exit codes: 0 accepted, 3 rejected, 4 no verdict (no STATUS came back).
#include <iostream>

#include "cli/command.h"
#include "cli/link_options.h"
#include "host/stream/link_stream.h"

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
  LinkStream stream(opt);
  stream.start();
  const CommandReply r = stream.command(*spec, values, std::chrono::milliseconds(a.timeout_ms));
  stream.stop();
  std::cout << a.name << " (type 0x" << std::hex << int(r.type) << std::dec << ", seq "
            << int(r.seq) << "): " << r.message << "\n";
  if (r.ack != Ack::Pending && spec->hall) print_hall_status(r.hall_status);
  else if (r.ack != Ack::Pending) print_status(r.status);
  switch (r.ack) {
    case Ack::Accepted: return 0;
    case Ack::Rejected: return 3;
    case Ack::Unknown: return 4;
    case Ack::Pending: break;
  }
  return 4;
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
