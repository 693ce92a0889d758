#include "host/stream/endpoint.h"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

namespace eskin::stream {

namespace detail {
int set_baud_termios2(int fd, int baud);
int get_baud_termios2(int fd);
}  // namespace detail

namespace {

std::string errno_text(int e) { return std::strerror(e); }

int open_serial(const Endpoint& ep) {
  const int fd = ::open(ep.path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw LinkError(ep.path + ": cannot open: " + errno_text(errno));
  try {
    configure_serial(fd, ep.baud, ep.path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  return fd;
}

int open_tcp(const Endpoint& ep) {
  const std::string where = "tcp " + ep.host + ":" + std::to_string(ep.port);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  const int rc = getaddrinfo(ep.host.c_str(), std::to_string(ep.port).c_str(), &hints, &res);
  if (rc != 0) throw LinkError(where + ": cannot resolve host: " + gai_strerror(rc));
  std::string last = "no address";
  for (addrinfo* a = res; a; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) {
      last = errno_text(errno);
      continue;
    }
    if (::connect(fd, a->ai_addr, a->ai_addrlen) == 0) {
      freeaddrinfo(res);
      const int one = 1;  // small frames: do not wait to coalesce commands
      setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
      fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
      return fd;
    }
    last = errno_text(errno);
    ::close(fd);
  }
  freeaddrinfo(res);
  throw LinkError(where + ": cannot connect: " + last);
}

speed_t standard_speed(int baud) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 500000: return B500000;
    case 921600: return B921600;
    case 1000000: return B1000000;
    case 2000000: return B2000000;
    case 3000000: return B3000000;
    case 4000000: return B4000000;
    default: return B0;
  }
}

}  // namespace

Endpoint Endpoint::serial(std::string path, int baud) {
  return {Kind::Serial, std::move(path), baud, "", 0};
}

Endpoint Endpoint::tcp(std::string host, uint16_t port) {
  return {Kind::Tcp, "", kBoardBaud, std::move(host), port};
}

Endpoint Endpoint::parse_tcp(const std::string& s) {
  std::string host;
  std::string port;
  if (!s.empty() && s[0] == '[') {
    const size_t close = s.find(']');
    if (close == std::string::npos || close + 1 >= s.size() || s[close + 1] != ':')
      throw LinkError("--tcp '" + s + "': expected [IPV6]:PORT");
    host = s.substr(1, close - 1);
    port = s.substr(close + 2);
  } else {
    const size_t colon = s.rfind(':');
    if (colon == std::string::npos || colon == 0)
      throw LinkError("--tcp '" + s + "': expected HOST:PORT");
    host = s.substr(0, colon);
    port = s.substr(colon + 1);
  }
  char* end = nullptr;
  const long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end || p < 1 || p > 65535)
    throw LinkError("--tcp '" + s + "': port must be 1..65535, got '" + port + "'");
  return tcp(host, uint16_t(p));
}

std::string Endpoint::describe() const {
  if (kind == Kind::Tcp) return "tcp " + host + ":" + std::to_string(port);
  return path + " @ " + std::to_string(baud) + " baud";
}

void configure_serial(int fd, int baud, const std::string& name) {
  if (baud <= 0) throw LinkError(name + ": baud rate must be positive, got " + std::to_string(baud));
  termios t{};
  if (tcgetattr(fd, &t) != 0)
    throw LinkError(name + ": not a serial device (tcgetattr: " + errno_text(errno) + ")");
  cfmakeraw(&t);  // 8 bits, no parity, no echo, no translation
  t.c_cflag &= ~tcflag_t(CSTOPB | CRTSCTS | PARENB);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_iflag &= ~tcflag_t(IXON | IXOFF | IXANY);
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  const speed_t sp = standard_speed(baud);
  if (sp != B0) cfsetspeed(&t, sp);
  if (tcsetattr(fd, TCSANOW, &t) != 0)
    throw LinkError(name + ": cannot set raw mode: " + errno_text(errno));
  if (sp == B0 && detail::set_baud_termios2(fd, baud) != 0)
    throw LinkError(name + ": cannot set " + std::to_string(baud) +
                    " baud (termios2 BOTHER): " + errno_text(errno));
  tcflush(fd, TCIFLUSH);  // bytes from before we set the line up are noise
}

int serial_baud(int fd) { return detail::get_baud_termios2(fd); }

Channel::Channel(const Endpoint& ep)
    : fd_(ep.kind == Endpoint::Kind::Tcp ? open_tcp(ep) : open_serial(ep)),
      socket_(ep.kind == Endpoint::Kind::Tcp),
      name_(ep.describe()) {}

Channel::~Channel() { close(); }

Channel::Channel(Channel&& o) noexcept
    : fd_(o.fd_), socket_(o.socket_), name_(std::move(o.name_)) {
  o.fd_ = -1;
}

Channel& Channel::operator=(Channel&& o) noexcept {
  if (this != &o) {
    close();
    fd_ = o.fd_;
    socket_ = o.socket_;
    name_ = std::move(o.name_);
    o.fd_ = -1;
  }
  return *this;
}

void Channel::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

ReadStatus Channel::read(uint8_t* buf, size_t cap, size_t& got, int timeout_ms,
                         std::string* why) {
  got = 0;
  if (fd_ < 0) {
    if (why) *why = "not open";
    return ReadStatus::Closed;
  }
  pollfd p{fd_, POLLIN, 0};
  const int r = ::poll(&p, 1, timeout_ms);
  if (r < 0) {
    if (errno == EINTR) return ReadStatus::Timeout;
    if (why) *why = name_ + ": poll: " + errno_text(errno);
    return ReadStatus::Closed;
  }
  if (r == 0) return ReadStatus::Timeout;
  // POLLHUP with data still buffered: read it first; read() then reports the end.
  const ssize_t n = ::read(fd_, buf, cap);
  if (n > 0) {
    got = size_t(n);
    return ReadStatus::Data;
  }
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return ReadStatus::Timeout;
  if (why) *why = name_ + (n == 0 ? ": end of stream" : ": read: " + errno_text(errno));
  return ReadStatus::Closed;
}

void Channel::write_all(const uint8_t* data, size_t n, int timeout_ms) {
  using clock = std::chrono::steady_clock;
  const auto deadline = clock::now() + std::chrono::milliseconds(timeout_ms);
  while (n > 0) {
    if (fd_ < 0) throw LinkError(name_ + ": write: link is closed");
    // MSG_NOSIGNAL: a peer that went away is an error here, not a SIGPIPE.
    const ssize_t w = socket_ ? ::send(fd_, data, n, MSG_NOSIGNAL) : ::write(fd_, data, n);
    if (w > 0) {
      data += w;
      n -= size_t(w);
      continue;
    }
    if (w < 0 && errno != EAGAIN && errno != EINTR)
      throw LinkError(name_ + ": write: " + errno_text(errno));
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock::now()).count();
    if (left <= 0) throw LinkError(name_ + ": write: timed out");
    pollfd p{fd_, POLLOUT, 0};
    ::poll(&p, 1, int(left));
  }
}

}  // namespace eskin::stream
