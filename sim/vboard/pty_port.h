// The host side of the virtual board's USB serial port: a pseudo-terminal
// pair. The host program opens the slave (/dev/pts/N) exactly like a real
// /dev/ttyUSB0 and sets its baud rate with termios; the board holds the
// master and reads the rate the reader configured (on Linux the master
// sees the slave's termios).
//
// The slave starts raw at speed B0 ("not configured"), so the board can
// tell when a reader has opened and configured the port.
//
// Linux pty semantics the board relies on (checked by experiment, and by
// tests/vboard and tests/stream/vboard_stream_test.cpp):
//  - after the slave's last close the master polls POLLHUP, until the
//    slave is opened again, which works while the master is open;
//  - the slave's termios (raw mode, the reader's baud rate) outlive that
//    close: a reopening reader finds the last rate, as a USB serial
//    adapter's driver keeps its settings;
//  - bytes written to the master while nobody has the slave open are kept
//    (about 12 KB, then writes would block) for the next reader;
//  - closing the master discards what the reader has not read yet and the
//    slave device goes away (its next read returns end of file, a new open
//    of /dev/pts/N fails): a board hangs up only once the reader has read
//    everything (unread() is 0).
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
  // Bytes written to the master that the reader has not read yet (FIONREAD
  // on a descriptor of the slave opened for the question); -1 when it
  // cannot be known (the slave refused a second open: TIOCEXCL).
  long unread() const;
  // The board hangs up: closes the master (the reader sees end of file) and
  // removes the symlink.
  void hang_up();
  bool hung_up() const { return fd_ < 0; }

 private:
  int fd_ = -1;
  std::string slave_, link_;
};

}  // namespace eskin::vboard
