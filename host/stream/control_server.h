// Commands to a running stream: `eskin stream` owns the port (port_lock.h),
// so whoever else wants to configure the board sends its command through
// the stream, which writes it on the link it already reads and judges the
// verdict from the STATUS packets it already receives (LinkStream::command).
//
// Protocol: one JSON line in, one JSON line out, then the connection closes.
//   request  {"command": "set-mask", "args": ["0x7"], "timeout_ms": 2000}
//            (args and timeout_ms optional; args are strings as on the
//            command line)
//   reply    {"ok": true, "command": "set-mask", "args": ["0x7"],
//             "ack": "accepted" | "rejected" | "unknown" | "no_verdict",
//             "exit": 0 | 3 | 4, "message": "accepted", "type": 132, "seq": 1,
//             "hall": false, "status": {cmd_accepted, ...} | null,
//             "hall_status": {...} | null}
//            {"ok": false, "error": "unknown command 'x'; ...", "exit": 2}
//            (exit 2: a bad request; 1: the link is not open)
// "exit" is what `eskin config` exits with (eskin/exit_codes.h).
//
// ControlServer serves it on a Unix domain socket (mode 0600, in the 0700
// runtime directory), one connection at a time, and through handle() to
// anyone else in the process (the live view's form).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "host/stream/link_stream.h"
#include "host/stream/recorder.h"

namespace eskin::stream {

// One command the stream carried out (or tried to), for its recordings.
struct CommandOutcome {
  int64_t host_ms = 0;  // wall clock when the verdict came, ms since the Unix epoch
  std::string command;
  std::vector<std::string> args;
  CommandReply reply;   // reply.ack Pending: no verdict in time
  std::string error;    // not sent: the link was not open (reply unset)
};

// "accepted", "rejected", "unknown", "no_verdict"; "error" when not sent.
std::string ack_name(const CommandOutcome& o);
// 0 accepted, 3 rejected, 4 unknown or no verdict (eskin/exit_codes.h).
int ack_exit_code(Ack a);

// The outcome as the recordings hold it (recorder.h).
CommandRecord command_record(const CommandOutcome& o);

// The reply line for an outcome, and back (for `eskin config`): throws
// std::runtime_error naming what is missing from a malformed reply.
std::string reply_json(const CommandOutcome& o, bool hall);
CommandReply reply_from_json(const std::string& line);

class ControlServer {
 public:
  using VerdictFn = std::function<void(const CommandOutcome&)>;

  // Binds socket_path (a stale socket there is removed: the caller holds
  // the port's lock, so no live stream serves it) and serves on its own
  // thread. on_verdict is called after every command that was sent or
  // failed to send, from the serving thread or a handle() caller's: it
  // must be thread-safe. Throws std::runtime_error naming the path.
  ControlServer(LinkStream& stream, std::string socket_path, VerdictFn on_verdict);
  ~ControlServer();  // stops serving, removes the socket
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;

  const std::string& path() const { return path_; }
  // One request line -> one reply line (no newline). Thread-safe; commands
  // go out one at a time (LinkStream::command serialises them).
  std::string handle(const std::string& request_json);

 private:
  void serve();
  void serve_one(int fd);

  LinkStream& stream_;
  std::string path_;
  VerdictFn on_verdict_;
  int listen_fd_ = -1;
  int wake_[2] = {-1, -1};  // a pipe: written to stop the serving thread
  std::thread thread_;
};

// Nothing listens on the control socket (the connect failed): the request
// did not reach a stream, so it may be sent again or elsewhere.
class ControlUnreachable : public LinkError {
 public:
  using LinkError::LinkError;
};

// The client end (`eskin config`): sends one request to the stream serving
// socket_path and returns its reply line. Throws ControlUnreachable when
// nothing listens there, LinkError when the request went out but no reply
// came within `timeout` (the command may have been applied: do not resend).
std::string control_request(const std::string& socket_path, const std::string& request_json,
                            std::chrono::milliseconds timeout);

// The request line for a command.
std::string request_json(const std::string& command, const std::vector<std::string>& args,
                         int timeout_ms);

}  // namespace eskin::stream
