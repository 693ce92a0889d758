#include "host/stream/control_server.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "eskin/exit_codes.h"

namespace eskin::stream {

namespace {

using nlohmann::json;

// How long a client may take to send its request line.
constexpr int kRequestMs = 5000;
constexpr size_t kMaxRequest = 64 * 1024;

json status_json(const link::StatusBlock& s) {
  return {{"cmd_crc_errors", s.cmd_crc_errors},   {"cmd_frame_errors", s.cmd_frame_errors},
          {"cmd_accepted", s.cmd_accepted},       {"cmd_rejected", s.cmd_rejected},
          {"last_reject_type", s.last_reject_type}, {"last_reject_reason", s.last_reject_reason},
          {"last_reject_seq", s.last_reject_seq}, {"output_mask", s.output_mask},
          {"dropped_frames", s.dropped_frames},   {"adc_overruns", s.adc_overruns},
          {"uart_rx_errors", s.uart_rx_errors},   {"frame_overruns", s.frame_overruns},
          {"spikes_dropped", s.spikes_dropped},   {"cmd_overflows", s.cmd_overflows},
          {"samples", s.samples}};
}

json hall_status_json(const link::HallDecodeStatus& s) {
  return {{"baseline_dropped", s.baseline_dropped}, {"ft_skipped", s.ft_skipped},
          {"cmd_accepted", s.cmd_accepted},         {"cmd_rejected", s.cmd_rejected},
          {"cmd_crc_errors", s.cmd_crc_errors},     {"cmd_frame_errors", s.cmd_frame_errors},
          {"cmd_overflows", s.cmd_overflows},       {"last_reject_type", s.last_reject_type},
          {"last_reject_reason", s.last_reject_reason}, {"last_reject_seq", s.last_reject_seq}};
}

template <class T>
void field(const json& j, const char* name, T& out) {
  if (!j.contains(name) || !j[name].is_number_integer())
    throw std::runtime_error(std::string("control reply: field '") + name +
                             "' missing or not an integer");
  out = j[name].get<T>();
}

link::StatusBlock status_from(const json& j) {
  link::StatusBlock s;
  field(j, "cmd_crc_errors", s.cmd_crc_errors), field(j, "cmd_frame_errors", s.cmd_frame_errors);
  field(j, "cmd_accepted", s.cmd_accepted), field(j, "cmd_rejected", s.cmd_rejected);
  field(j, "last_reject_type", s.last_reject_type);
  field(j, "last_reject_reason", s.last_reject_reason);
  field(j, "last_reject_seq", s.last_reject_seq), field(j, "output_mask", s.output_mask);
  field(j, "dropped_frames", s.dropped_frames), field(j, "adc_overruns", s.adc_overruns);
  field(j, "uart_rx_errors", s.uart_rx_errors), field(j, "frame_overruns", s.frame_overruns);
  field(j, "spikes_dropped", s.spikes_dropped), field(j, "cmd_overflows", s.cmd_overflows);
  field(j, "samples", s.samples);
  return s;
}

link::HallDecodeStatus hall_status_from(const json& j) {
  link::HallDecodeStatus s;
  field(j, "baseline_dropped", s.baseline_dropped), field(j, "ft_skipped", s.ft_skipped);
  field(j, "cmd_accepted", s.cmd_accepted), field(j, "cmd_rejected", s.cmd_rejected);
  field(j, "cmd_crc_errors", s.cmd_crc_errors), field(j, "cmd_frame_errors", s.cmd_frame_errors);
  field(j, "cmd_overflows", s.cmd_overflows), field(j, "last_reject_type", s.last_reject_type);
  field(j, "last_reject_reason", s.last_reject_reason);
  field(j, "last_reject_seq", s.last_reject_seq);
  return s;
}

std::string error_reply(const std::string& what, Exit code) {
  return json{{"ok", false}, {"error", what}, {"exit", exit_code(code)}}.dump();
}

int64_t now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

std::string ack_name(const CommandOutcome& o) {
  if (!o.error.empty()) return "error";
  switch (o.reply.ack) {
    case Ack::Accepted: return "accepted";
    case Ack::Rejected: return "rejected";
    case Ack::Unknown: return "unknown";
    case Ack::Pending: break;
  }
  return "no_verdict";
}

int ack_exit_code(Ack a) {
  switch (a) {
    case Ack::Accepted: return exit_code(Exit::ok);
    case Ack::Rejected: return exit_code(Exit::rejected);
    case Ack::Unknown:
    case Ack::Pending: break;
  }
  return exit_code(Exit::no_verdict);
}

CommandRecord command_record(const CommandOutcome& o) {
  CommandRecord c;
  c.host_ms = o.host_ms;
  c.command = o.command;
  c.args = o.args;
  c.ack = ack_name(o);
  c.message = o.error.empty() ? o.reply.message : o.error;
  c.cmd_type = o.reply.type;
  c.seq = o.reply.seq;
  const bool hall = find_command(o.command) && find_command(o.command)->hall;
  if (o.error.empty() && o.reply.ack != Ack::Pending && !hall) c.samples = o.reply.status.samples;
  return c;
}

std::string reply_json(const CommandOutcome& o, bool hall) {
  if (!o.error.empty()) return error_reply(o.error, Exit::failure);
  const CommandReply& r = o.reply;
  const bool decided = r.ack != Ack::Pending;
  json j = {{"ok", true},
            {"command", o.command},
            {"args", o.args},
            {"ack", ack_name(o)},
            {"exit", ack_exit_code(r.ack)},
            {"message", r.message},
            {"type", r.type},
            {"seq", r.seq},
            {"hall", hall},
            {"status", decided && !hall ? status_json(r.status) : json(nullptr)},
            {"hall_status", decided && hall ? hall_status_json(r.hall_status) : json(nullptr)}};
  return j.dump();
}

CommandReply reply_from_json(const std::string& line) {
  json j;
  try {
    j = json::parse(line);
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("control reply is not JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("ack") || !j["ack"].is_string() || !j.contains("message") ||
      !j["message"].is_string())
    throw std::runtime_error("control reply: expected an object with 'ack' and 'message'");
  CommandReply r;
  const std::string ack = j["ack"].get<std::string>();
  r.ack = ack == "accepted"   ? Ack::Accepted
          : ack == "rejected" ? Ack::Rejected
          : ack == "unknown"  ? Ack::Unknown
                              : Ack::Pending;
  if (r.ack == Ack::Pending && ack != "no_verdict")
    throw std::runtime_error("control reply: unknown ack '" + ack + "'");
  r.message = j["message"].get<std::string>();
  field(j, "type", r.type);
  field(j, "seq", r.seq);
  if (j.contains("status") && j["status"].is_object()) r.status = status_from(j["status"]);
  if (j.contains("hall_status") && j["hall_status"].is_object())
    r.hall_status = hall_status_from(j["hall_status"]);
  return r;
}

std::string request_json(const std::string& command, const std::vector<std::string>& args,
                         int timeout_ms) {
  return json{{"command", command}, {"args", args}, {"timeout_ms", timeout_ms}}.dump();
}

ControlServer::ControlServer(LinkStream& stream, std::string socket_path, VerdictFn on_verdict)
    : stream_(stream), path_(std::move(socket_path)), on_verdict_(std::move(on_verdict)) {
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  if (path_.size() >= sizeof a.sun_path)
    throw std::runtime_error(path_ + ": control socket path too long");
  std::memcpy(a.sun_path, path_.c_str(), path_.size() + 1);
  ::unlink(path_.c_str());  // a stale socket of a stream that was killed
  listen_fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0 || ::bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::chmod(path_.c_str(), 0600) != 0 || ::listen(listen_fd_, 8) != 0 ||
      ::pipe2(wake_, O_CLOEXEC) != 0) {
    const std::string why = std::strerror(errno);
    if (listen_fd_ >= 0) ::close(listen_fd_);
    ::unlink(path_.c_str());
    throw std::runtime_error(path_ + ": cannot serve the control socket: " + why);
  }
  thread_ = std::thread([this] { serve(); });
}

ControlServer::~ControlServer() {
  if (wake_[1] >= 0) {
    const char c = 'x';
    const ssize_t w = ::write(wake_[1], &c, 1);
    (void)w;  // the pipe is empty: a one-byte write cannot fail short
  }
  if (thread_.joinable()) thread_.join();
  ::close(listen_fd_);
  ::close(wake_[0]);
  ::close(wake_[1]);
  ::unlink(path_.c_str());
}

void ControlServer::serve() {
  while (true) {
    pollfd p[2] = {{listen_fd_, POLLIN, 0}, {wake_[0], POLLIN, 0}};
    if (::poll(p, 2, -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    if (p[1].revents) return;
    if (!(p[0].revents & POLLIN)) continue;
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    serve_one(fd);
    ::close(fd);
  }
}

void ControlServer::serve_one(int fd) {
  std::string line;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(kRequestMs);
  char buf[4096];
  while (line.find('\n') == std::string::npos && line.size() < kMaxRequest) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          end - std::chrono::steady_clock::now())
                          .count();
    pollfd p[2] = {{fd, POLLIN, 0}, {wake_[0], POLLIN, 0}};
    if (left <= 0 || ::poll(p, 2, int(left)) <= 0 || p[1].revents) return;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) break;  // a request without its newline is taken as it is
    line.append(buf, size_t(n));
  }
  const std::string reply = handle(line.substr(0, line.find('\n'))) + "\n";
  size_t off = 0;
  while (off < reply.size()) {
    const ssize_t w = ::send(fd, reply.data() + off, reply.size() - off, MSG_NOSIGNAL);
    if (w <= 0) return;  // the client went away: its loss
    off += size_t(w);
  }
}

std::string ControlServer::handle(const std::string& request) {
  json j;
  try {
    j = json::parse(request);
  } catch (const json::exception& e) {
    return error_reply(std::string("request is not JSON: ") + e.what(), Exit::usage);
  }
  if (!j.is_object() || !j.contains("command") || !j["command"].is_string())
    return error_reply("request: expected {\"command\": NAME, \"args\": [strings]}", Exit::usage);
  CommandOutcome o;
  o.command = j["command"].get<std::string>();
  if (j.contains("args")) {
    if (!j["args"].is_array())
      return error_reply("request: 'args' must be an array of strings", Exit::usage);
    for (const json& a : j["args"]) {
      if (!a.is_string())
        return error_reply("request: 'args' must be an array of strings, got " + a.dump(),
                           Exit::usage);
      o.args.push_back(a.get<std::string>());
    }
  }
  int timeout_ms = 2000;
  if (j.contains("timeout_ms")) {
    if (!j["timeout_ms"].is_number_integer() || j["timeout_ms"].get<int64_t>() < 10 ||
        j["timeout_ms"].get<int64_t>() > 60000)
      return error_reply("request: 'timeout_ms' must be an integer 10..60000", Exit::usage);
    timeout_ms = j["timeout_ms"].get<int>();
  }
  const CommandSpec* spec = find_command(o.command);
  std::vector<int64_t> values;
  try {
    if (!spec) {
      std::string known;
      for (const CommandSpec& c : command_specs()) known += std::string(" ") + c.name;
      throw std::invalid_argument("unknown command '" + o.command + "'; expected one of:" + known);
    }
    values = parse_command_args(*spec, o.args);
  } catch (const std::invalid_argument& e) {
    return error_reply(e.what(), Exit::usage);
  }
  o.reply.type = spec->type;  // also when it cannot be sent
  try {
    o.reply = stream_.command(*spec, values, std::chrono::milliseconds(timeout_ms));
  } catch (const std::exception& e) {  // LinkError: the link is down
    o.error = e.what();
  }
  o.host_ms = now_ms();
  if (on_verdict_) on_verdict_(o);
  return reply_json(o, spec->hall);
}

std::string control_request(const std::string& socket_path, const std::string& request,
                            std::chrono::milliseconds timeout) {
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  if (socket_path.size() >= sizeof a.sun_path)
    throw LinkError(socket_path + ": control socket path too long");
  std::memcpy(a.sun_path, socket_path.c_str(), socket_path.size() + 1);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw LinkError(std::string("socket: ") + std::strerror(errno));
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw ControlUnreachable(socket_path + ": cannot connect: " + why);
  }
  const std::string line = request + "\n";
  size_t off = 0;
  while (off < line.size()) {
    const ssize_t w = ::send(fd, line.data() + off, line.size() - off, MSG_NOSIGNAL);
    if (w <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw LinkError(socket_path + ": cannot send the request: " + why);
    }
    off += size_t(w);
  }
  std::string reply;
  const auto end = std::chrono::steady_clock::now() + timeout;
  char buf[4096];
  while (reply.find('\n') == std::string::npos) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          end - std::chrono::steady_clock::now())
                          .count();
    pollfd p{fd, POLLIN, 0};
    if (left <= 0 || ::poll(&p, 1, int(left)) <= 0) {
      ::close(fd);
      throw LinkError(socket_path + ": no reply from the stream within " +
                      std::to_string(timeout.count()) + " ms");
    }
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) {
      ::close(fd);
      throw LinkError(socket_path + ": the stream closed the connection without a reply");
    }
    reply.append(buf, size_t(n));
  }
  ::close(fd);
  return reply.substr(0, reply.find('\n'));
}

}  // namespace eskin::stream
