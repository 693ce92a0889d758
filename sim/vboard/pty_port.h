// The host side of the virtual board's USB serial port: a pseudo-terminal
// pair. The host program opens the slave (/dev/pts/N) exactly like a real
// /dev/ttyUSB0 and sets its baud rate with termios; the board holds the
// master and reads the rate the reader configured (on Linux the master
// sees the slave's termios).
//
// The slave starts raw at speed B0 ("not configured"), so the board can
// tell when a reader has opened and configured the port.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace eskin::vboard {

class PtyPort {
 public:
  PtyPort();  // throws std::runtime_error naming the failing call
  ~PtyPort();
  PtyPort(const PtyPort&) = delete;
  PtyPort& operator=(const PtyPort&) = delete;

  const std::string& slave_path() const { return slave_; }
  // A symlink at `path` to the slave (replaced if it exists; removed on exit).
  void link(const std::string& path);

  // Output speed in baud the reader set on its side (0: B0, not set yet).
  double reader_baud() const;
  // The reader closed the slave (POLLHUP on the master).
  bool reader_closed() const;
  // Non-blocking; return the bytes moved (0 when none can be).
  size_t read(uint8_t* buf, size_t n);
  size_t write(const uint8_t* buf, size_t n);
  // Blocks until the master can take more bytes, the reader closes, or
  // timeout_ms passes; false on timeout or close.
  bool wait_writable(int timeout_ms);

 private:
  int fd_ = -1;
  std::string slave_, link_;
};

}  // namespace eskin::vboard
