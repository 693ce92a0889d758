// Byte channels to the board: a serial device (also the virtual board's
// pty) or a TCP server. A Channel is one open file descriptor; the stream
// (link_stream.h) reopens it from its Endpoint when the link drops.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace eskin::stream {

// The board's UART rate (docs/protocol.md §2).
constexpr int kBoardBaud = 3000000;

// Open/read/write failure; what() names the device or address.
class LinkError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Endpoint {
  enum class Kind { Serial, Tcp };
  Kind kind = Kind::Serial;
  std::string path;    // Serial: device or pty path
  int baud = kBoardBaud;
  std::string host;    // Tcp
  uint16_t port = 0;

  static Endpoint serial(std::string path, int baud = kBoardBaud);
  static Endpoint tcp(std::string host, uint16_t port);
  // "HOST:PORT" (IPv6 as "[::1]:PORT"); throws LinkError naming what is wrong.
  static Endpoint parse_tcp(const std::string& host_port);
  std::string describe() const;  // "/dev/ttyUSB1 @ 3000000 baud", "tcp 127.0.0.1:9000"
};

// Result of one Channel::read.
enum class ReadStatus { Data, Timeout, Closed };

class Channel {
 public:
  Channel() = default;
  explicit Channel(const Endpoint& ep);  // opens; throws LinkError
  ~Channel();
  Channel(Channel&& o) noexcept;
  Channel& operator=(Channel&& o) noexcept;
  Channel(const Channel&) = delete;
  Channel& operator=(const Channel&) = delete;

  bool is_open() const { return fd_ >= 0; }
  int fd() const { return fd_; }
  // Waits up to timeout_ms for bytes. Closed: EOF, EIO (pty master gone,
  // USB device removed) or a socket error; *why then says which.
  ReadStatus read(uint8_t* buf, size_t cap, size_t& got, int timeout_ms, std::string* why);
  // Writes everything (waiting up to timeout_ms in total); throws LinkError.
  void write_all(const uint8_t* data, size_t n, int timeout_ms = 1000);
  void close();

 private:
  int fd_ = -1;
  bool socket_ = false;
  std::string name_;
};

// Serial line set-up on an open descriptor: raw 8N1, no flow control,
// receiver on, the given baud rate (any rate: non-standard ones through
// termios2/BOTHER). Throws LinkError naming `name`.
void configure_serial(int fd, int baud, const std::string& name);
// The baud rate the driver reports for fd (termios2: exact for any rate).
int serial_baud(int fd);

}  // namespace eskin::stream
