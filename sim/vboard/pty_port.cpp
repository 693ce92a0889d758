#include "sim/vboard/pty_port.h"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace eskin::vboard {

// serial_speed.cpp: the exact output speed of an arbitrary-rate (BOTHER)
// setting, read with TCGETS2 (its header clashes with <termios.h>).
double termios2_output_speed(int fd);

namespace {

[[noreturn]] void fail(const char* call) {
  throw std::runtime_error(std::string("virtual board serial port: ") + call + ": " +
                           std::strerror(errno));
}

double speed_of(speed_t s) {
  static const struct { speed_t code; double baud; } kSpeeds[] = {
      {B0, 0},           {B50, 50},           {B75, 75},           {B110, 110},
      {B134, 134},       {B150, 150},         {B200, 200},         {B300, 300},
      {B600, 600},       {B1200, 1200},       {B1800, 1800},       {B2400, 2400},
      {B4800, 4800},     {B9600, 9600},       {B19200, 19200},     {B38400, 38400},
      {B57600, 57600},   {B115200, 115200},   {B230400, 230400},   {B460800, 460800},
      {B500000, 500000}, {B576000, 576000},   {B921600, 921600},   {B1000000, 1000000},
      {B1152000, 1152000}, {B1500000, 1500000}, {B2000000, 2000000}, {B2500000, 2500000},
      {B3000000, 3000000}, {B3500000, 3500000}, {B4000000, 4000000}};
  for (const auto& e : kSpeeds)
    if (e.code == s) return e.baud;
  return -1;  // BOTHER: ask termios2
}

}  // namespace

PtyPort::PtyPort() {
  fd_ = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd_ < 0) fail("posix_openpt");
  if (grantpt(fd_) != 0) fail("grantpt");
  if (unlockpt(fd_) != 0) fail("unlockpt");
  const char* name = ptsname(fd_);
  if (!name) fail("ptsname");
  slave_ = name;
  // Raw bytes both ways (no echo, no line editing, no CR/LF mapping), and
  // speed B0 until a reader sets its rate. Set through the master: the
  // slave's termios is the one that counts.
  termios t{};
  if (tcgetattr(fd_, &t) != 0) fail("tcgetattr");
  cfmakeraw(&t);
  cfsetispeed(&t, B0);
  cfsetospeed(&t, B0);
  if (tcsetattr(fd_, TCSANOW, &t) != 0) fail("tcsetattr");
}

PtyPort::~PtyPort() { hang_up(); }

void PtyPort::hang_up() {
  if (!link_.empty()) ::unlink(link_.c_str());
  link_.clear();
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

long PtyPort::unread() const {
  if (fd_ < 0) return 0;
  // TIOCGPTPEER opens this master's own slave (no path lookup, no race
  // with another pty taking the name).
  int s = -1;
#ifdef TIOCGPTPEER
  s = ::ioctl(fd_, TIOCGPTPEER, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
#endif
  if (s < 0) s = ::open(slave_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (s < 0) return -1;
  int n = 0;
  const int rc = ::ioctl(s, FIONREAD, &n);
  ::close(s);
  return rc == 0 ? long(n) : -1;
}

void PtyPort::link(const std::string& path) {
  ::unlink(path.c_str());
  if (::symlink(slave_.c_str(), path.c_str()) != 0)
    throw std::runtime_error("virtual board serial port: cannot link " + path + " -> " + slave_ +
                             ": " + std::strerror(errno));
  link_ = path;
}

double PtyPort::reader_baud() const {
  termios t{};
  if (tcgetattr(fd_, &t) != 0) return 0;
  const double b = speed_of(cfgetospeed(&t));
  return b >= 0 ? b : termios2_output_speed(fd_);
}

bool PtyPort::reader_closed() const {
  pollfd p{fd_, POLLIN, 0};
  return ::poll(&p, 1, 0) > 0 && (p.revents & POLLHUP);
}

size_t PtyPort::read(uint8_t* buf, size_t n) {
  const ssize_t r = ::read(fd_, buf, n);
  return r > 0 ? size_t(r) : 0;  // EAGAIN (nothing), EIO (no reader): nothing
}

size_t PtyPort::write(const uint8_t* buf, size_t n) {
  const ssize_t w = ::write(fd_, buf, n);
  return w > 0 ? size_t(w) : 0;
}

bool PtyPort::wait_writable(int timeout_ms) {
  pollfd p{fd_, POLLOUT, 0};
  if (::poll(&p, 1, timeout_ms) <= 0) return false;
  return (p.revents & POLLOUT) && !(p.revents & POLLHUP);
}

}  // namespace eskin::vboard
