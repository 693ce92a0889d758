// Test fixtures made of real kernel objects: a pseudo-terminal pair
// (posix_openpt) standing in for the board's USB serial port, whose slave
// path the library opens like /dev/ttyUSB0, and a loopback TCP server.
#pragma once

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace eskin::testing {

// Writes everything to fd (blocking the caller while the peer is slow).
inline bool write_fully(int fd, const uint8_t* p, size_t n) {
  while (n > 0) {
    const ssize_t w = ::send(fd, p, n, MSG_NOSIGNAL);
    const ssize_t r = (w < 0 && errno == ENOTSOCK) ? ::write(fd, p, n) : w;
    if (r < 0 && errno == EAGAIN) {
      pollfd q{fd, POLLOUT, 0};
      ::poll(&q, 1, 100);
      continue;
    }
    if (r <= 0) return false;
    p += r;
    n -= size_t(r);
  }
  return true;
}
inline bool write_fully(int fd, const std::vector<uint8_t>& v) {
  return write_fully(fd, v.data(), v.size());
}

// Reads what is there within timeout_ms (empty on timeout / end).
inline std::vector<uint8_t> read_some(int fd, int timeout_ms) {
  pollfd q{fd, POLLIN, 0};
  std::vector<uint8_t> b;
  if (::poll(&q, 1, timeout_ms) <= 0) return b;
  b.resize(4096);
  const ssize_t n = ::read(fd, b.data(), b.size());
  b.resize(n > 0 ? size_t(n) : 0);
  return b;
}

class PtyPair {
 public:
  PtyPair() {
    // CLOEXEC: a child process (the eskin CLI under test) must not keep the
    // board alive by inheriting the master.
    master_ = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master_ < 0 || grantpt(master_) != 0 || unlockpt(master_) != 0)
      throw std::runtime_error("posix_openpt failed");
    slave_path_ = ptsname(master_);
    // Raw from the start, so nothing the test writes is echoed or translated
    // before the library has set the line up itself.
    const int s = ::open(slave_path_.c_str(), O_RDWR | O_NOCTTY);
    termios t{};
    tcgetattr(s, &t);
    cfmakeraw(&t);
    tcsetattr(s, TCSANOW, &t);
    ::close(s);
  }
  ~PtyPair() { close_master(); }
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  int master() const { return master_; }
  const std::string& slave_path() const { return slave_path_; }
  // The board goes away: the slave side then reads EIO / hang-up.
  void close_master() {
    if (master_ >= 0) ::close(master_);
    master_ = -1;
  }

 private:
  int master_ = -1;
  std::string slave_path_;
};

// A listening TCP socket on 127.0.0.1 with a kernel-chosen port.
class LoopbackServer {
 public:
  LoopbackServer() {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
        ::listen(fd_, 4) != 0 || getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0)
      throw std::runtime_error("loopback server: cannot listen");
    port_ = ntohs(a.sin_port);
  }
  ~LoopbackServer() { ::close(fd_); }
  uint16_t port() const { return port_; }
  // One client connection (-1 after timeout_ms).
  int accept_one(int timeout_ms = 5000) {
    pollfd q{fd_, POLLIN, 0};
    if (::poll(&q, 1, timeout_ms) <= 0) return -1;
    return ::accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC);
  }

 private:
  int fd_ = -1;
  uint16_t port_ = 0;
};

}  // namespace eskin::testing
