// One process owns a serial port. Two readers of one tty split its bytes
// between them (each sees half the frames, the rest as framing errors), so
// `eskin stream` and `eskin config` take an exclusive advisory lock on the
// port before they open it, and record who holds it; a second opener reads
// that record and says who holds the port instead of opening it.
//
// The lock is flock(LOCK_EX|LOCK_NB) on a per-user lock file named from the
// port's canonical path (realpath: a symlink such as the virtual board's
// and the /dev/pts/N it points to are one port), in the runtime directory:
//   $XDG_RUNTIME_DIR/eskin, or ${XDG_CACHE_HOME:-$HOME/.cache}/eskin/run
// (created 0700). The lock file also holds the record (pid, command, start
// time); the kernel drops the lock when its holder exits, however it ends,
// so a stale record is never believed. The same name with ".sock" is the
// holding stream's control socket (control_server.h).
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>

namespace eskin::stream {

// The runtime directory: eskin::user_runtime_dir() (eskin/user_dirs.h).
std::string runtime_dir();

// Where a port's lock, record and control socket live.
struct PortPaths {
  std::string port;       // as given (--port)
  std::string canonical;  // realpath of it (the path itself if it does not resolve)
  std::string lock;       // <runtime>/<name>.lock: the lock and the holder's record
  std::string socket;     // <runtime>/<name>.sock: the holding stream's control socket
};
// Throws std::runtime_error when the socket path would not fit a sockaddr_un.
PortPaths port_paths(const std::string& port);

// Who holds a port, as its holder recorded it.
struct PortHolder {
  pid_t pid = 0;             // 0: no readable record
  std::string command;       // "eskin stream", "eskin config"
  int64_t since_unix = 0;    // when it took the port (seconds since the epoch)
  bool serves_commands = false;  // it listens on PortPaths::socket
};

// "/dev/ttyUSB0 is held by eskin stream (pid 1234, since 12:03:04); ..."
std::string held_message(const PortPaths& p, const PortHolder& h);

class PortLock {
 public:
  PortLock() = default;
  ~PortLock() { release(); }
  PortLock(PortLock&& o) noexcept;
  PortLock& operator=(PortLock&& o) noexcept;
  PortLock(const PortLock&) = delete;
  PortLock& operator=(const PortLock&) = delete;

  // Takes the port without waiting and records this process as its holder
  // (`command`, and whether it will serve commands on the socket). False
  // when another process holds it; *holder then says who (its record is
  // re-read for up to 500 ms while the holder is still writing it). Throws
  // std::runtime_error when the lock file cannot be opened.
  bool try_acquire(const PortPaths& p, const std::string& command, bool serves_commands,
                   PortHolder* holder);
  bool held() const { return fd_ >= 0; }
  void release();

 private:
  int fd_ = -1;
};

}  // namespace eskin::stream
