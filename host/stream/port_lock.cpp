#include "host/stream/port_lock.h"

#include "eskin/fnv1a.h"
#include "eskin/user_dirs.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace eskin::stream {

namespace {

// A file name for the port: readable (its path's tail) and unique (a hash
// of the whole canonical path).
std::string port_name(const std::string& canonical) {
  std::string s;
  for (char c : canonical)
    s += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') ? c : '_';
  while (!s.empty() && s.front() == '_') s.erase(s.begin());
  if (s.size() > 32) s = s.substr(s.size() - 32);
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(eskin::fnv1a(canonical)));
  return s + "-" + hash;
}

std::string clock_time(int64_t unix_s) {
  const std::time_t t = std::time_t(unix_s);
  std::tm tm{};
  localtime_r(&t, &tm);
  char buf[16];
  std::strftime(buf, sizeof buf, "%H:%M:%S", &tm);
  return buf;
}

// The record in the lock file: "key=value" lines.
bool read_record(int fd, PortHolder& h) {
  char buf[512];
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return false;
  std::istringstream in(std::string(buf, size_t(n)));
  std::string line;
  PortHolder r;
  bool complete = false;
  while (std::getline(in, line)) {
    const size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string k = line.substr(0, eq), v = line.substr(eq + 1);
    if (k == "pid") r.pid = pid_t(std::atol(v.c_str()));
    if (k == "command") r.command = v;
    if (k == "since") r.since_unix = std::atoll(v.c_str());
    if (k == "serves_commands") r.serves_commands = v == "1";
    if (k == "end") complete = true;  // written last: the record is whole
  }
  if (!complete || r.pid <= 0) return false;
  h = r;
  return true;
}

}  // namespace

std::string runtime_dir() { return eskin::user_runtime_dir(); }

PortPaths port_paths(const std::string& port) {
  PortPaths p;
  p.port = port;
  char buf[PATH_MAX];
  p.canonical = ::realpath(port.c_str(), buf) ? std::string(buf) : port;
  const std::string base = runtime_dir() + "/" + port_name(p.canonical);
  p.lock = base + ".lock";
  p.socket = base + ".sock";
  if (p.socket.size() >= sizeof(sockaddr_un{}.sun_path))
    throw std::runtime_error(p.socket + ": the control socket's path is longer than " +
                             std::to_string(sizeof(sockaddr_un{}.sun_path) - 1) +
                             " bytes; set XDG_RUNTIME_DIR to a shorter directory");
  return p;
}

std::string held_message(const PortPaths& p, const PortHolder& h) {
  std::string port = p.port;
  if (p.canonical != p.port) port += " (" + p.canonical + ")";
  if (h.pid <= 0)
    return port + " is held by another process (its record " + p.lock + " is not readable)";
  std::string m = port + " is held by " + (h.command.empty() ? "a process" : h.command) +
                  " (pid " + std::to_string(h.pid) + ", since " + clock_time(h.since_unix) + ")";
  if (h.serves_commands)
    m += "; to send commands while it records use eskin config, which goes through it";
  else
    m += "; wait for it to finish";
  return m;
}

PortLock::PortLock(PortLock&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }

PortLock& PortLock::operator=(PortLock&& o) noexcept {
  if (this != &o) {
    release();
    fd_ = o.fd_;
    o.fd_ = -1;
  }
  return *this;
}

bool PortLock::try_acquire(const PortPaths& p, const std::string& command, bool serves_commands,
                           PortHolder* holder) {
  release();
  const int fd = ::open(p.lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (fd < 0)
    throw std::runtime_error(p.lock + ": cannot open the port's lock file: " +
                             std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    if (e != EWOULDBLOCK) {
      ::close(fd);
      throw std::runtime_error(p.lock + ": cannot lock: " + std::strerror(e));
    }
    // The holder writes its record right after it locks: give it a moment.
    PortHolder h;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
    while (!read_record(fd, h) && std::chrono::steady_clock::now() < end)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ::close(fd);
    if (holder) *holder = h;
    return false;
  }
  const std::string rec = "pid=" + std::to_string(::getpid()) + "\ncommand=" + command +
                          "\nsince=" + std::to_string(int64_t(std::time(nullptr))) +
                          "\nport=" + p.canonical +
                          "\nserves_commands=" + (serves_commands ? "1" : "0") + "\nend=1\n";
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, rec.data(), rec.size(), 0) != ssize_t(rec.size())) {
    const int e = errno;
    ::close(fd);
    throw std::runtime_error(p.lock + ": cannot write the holder's record: " + std::strerror(e));
  }
  fd_ = fd;
  return true;
}

void PortLock::release() {
  // The file stays: removing it while another process opens it would let
  // two processes lock two different files of the same name.
  if (fd_ >= 0) {
    // An empty record while the lock is still ours; if truncating fails the
    // record stays, but no one believes a record whose lock is free.
    const int rc = ::ftruncate(fd_, 0);
    (void)rc;
    ::close(fd_);
  }
  fd_ = -1;
}

}  // namespace eskin::stream
