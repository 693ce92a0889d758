// host/stream LinkStream over real byte channels: a pty pair (the board's
// USB serial port, and the virtual board's pty) and a loopback TCP socket.
// A writer thread plays the board and sends frames built by
// host/link/link_encoder (an implementation independent of the decoder);
// the library must deliver exactly those packets.
//
// Counting rules checked (docs/protocol.md §3): a frame with one payload
// byte changed is exactly one CRC error (the CRC detects every single-byte
// error: a burst of <= 8 bits); a frame whose delimiter is lost merges with
// the next one into exactly one framing error (the merged length field no
// longer matches); both lost frames then show as one sequence gap. A frame
// left out entirely is one gap of one packet.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <termios.h>
#include <thread>

#include "host/link/link_encoder.h"
#include "host/stream/link_stream.h"
#include "tests/stream/frames.h"
#include "tests/stream/pty_pair.h"

namespace {

using eskin::link::LinkEncoder;
using eskin::link::Packet;
using eskin::stream::Endpoint;
using eskin::stream::LinkEvent;
using eskin::stream::LinkStream;
using eskin::stream::StreamOptions;
using eskin::testing::PtyPair;
using eskin::testing::concat;
using eskin::testing::random_frames;
using eskin::testing::Sent;
using eskin::testing::write_fully;
using namespace std::chrono_literals;

void expect_same(const std::vector<Sent>& want, const std::vector<Packet>& got) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i].type, want[i].type) << i;
    EXPECT_EQ(got[i].seq, want[i].seq) << i;
    EXPECT_EQ(got[i].t, want[i].t) << i;
    EXPECT_EQ(got[i].payload, want[i].payload) << i;
  }
}

// Collects packets from the callback; waits for a count.
struct Collector {
  std::mutex mu;
  std::vector<Packet> got;
  std::vector<LinkEvent> events;
  void attach(LinkStream& s) {
    s.on_packet([this](const Packet& p) {
      std::lock_guard<std::mutex> lk(mu);
      got.push_back(p);
    });
    s.on_event([this](const LinkEvent& e) {
      std::lock_guard<std::mutex> lk(mu);
      events.push_back(e);
    });
  }
  bool wait_packets(size_t n, std::chrono::milliseconds timeout = 10s) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      {
        std::lock_guard<std::mutex> lk(mu);
        if (got.size() >= n) return true;
      }
      std::this_thread::sleep_for(5ms);
    }
    return false;
  }
  // The packets so far, copied under the lock (the stream's reader thread
  // may still be appending).
  std::vector<Packet> snapshot() {
    std::lock_guard<std::mutex> lk(mu);
    return got;
  }
  size_t count(LinkEvent::Kind k) {
    std::lock_guard<std::mutex> lk(mu);
    size_t c = 0;
    for (const auto& e : events) c += e.kind == k;
    return c;
  }
  bool wait_event(LinkEvent::Kind k, size_t n, std::chrono::milliseconds timeout = 10s) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      if (count(k) >= n) return true;
      std::this_thread::sleep_for(5ms);
    }
    return false;
  }
};

StreamOptions pty_options(const std::string& path) {
  StreamOptions o;
  o.endpoint = Endpoint::serial(path);
  o.backoff_min_ms = 10;
  o.backoff_max_ms = 100;
  return o;
}

// Starts `s` (with `c` attached), writes `wire` into the pty from a writer
// thread and waits until `n` packets arrived.
::testing::AssertionResult pump(LinkStream& s, Collector& c, const PtyPair& pty,
                                const std::vector<uint8_t>& wire, size_t n) {
  c.attach(s);
  s.start();
  if (!c.wait_event(LinkEvent::Kind::Opened, 1)) return ::testing::AssertionFailure() << "no open";
  std::thread writer([&] { write_fully(pty.master(), wire); });
  const bool all = c.wait_packets(n);
  writer.join();
  if (!all) return ::testing::AssertionFailure() << c.snapshot().size() << " of " << n << " packets";
  return ::testing::AssertionSuccess();
}

TEST(LinkStreamPty, DeliversEveryPacketToCallbackAndQueue) {
  PtyPair pty;
  std::vector<Sent> sent;
  const auto frames = random_frames(2000, 1, sent);
  LinkStream s(pty_options(pty.slave_path()));
  Collector c;
  ASSERT_TRUE(pump(s, c, pty, concat(frames), sent.size()));
  expect_same(sent, c.snapshot());
  // The queue is filled after the callback runs: pop until every packet
  // sent is out (each has arrived, so a long wait ends at once), then the
  // queue must be empty.
  std::vector<Packet> pulled;
  Packet p;
  while (pulled.size() < sent.size() && s.pop(p, 10s)) pulled.push_back(p);
  while (s.pop(p, 0ms)) pulled.push_back(p);
  expect_same(sent, pulled);
  const auto st = s.stats();
  EXPECT_EQ(st.link.frames_ok, sent.size());
  EXPECT_EQ(st.corrupt(), 0u);
  EXPECT_EQ(st.link.lost_packets, 0u);
  EXPECT_EQ(st.queue_dropped, 0u);
  EXPECT_EQ(st.packets_by_type.at(eskin::link::kSpikes), sent.size() / 5);
}

// The packets hls/dtmf_chain.h computes on the default scene are what the
// FPGA sends (tests/rtl/dtmf_top_test.cpp proves it packet for packet); with
// the FPGA's framing (LinkEncoder: seq per packet) they arrive unchanged.
TEST(LinkStreamPty, DefaultSceneChainPacketsArriveUnchanged) {
  std::vector<Sent> sent;
  const std::vector<uint8_t> wire = eskin::testing::scene_frames(sent);
  size_t spikes = 0;
  for (const auto& x : sent) spikes += x.type == eskin::link::kSpikes;
  ASSERT_GE(spikes, 10u) << "the default scene's presses must make spikes";

  PtyPair pty;
  LinkStream s(pty_options(pty.slave_path()));
  Collector c;
  ASSERT_TRUE(pump(s, c, pty, wire, sent.size()));
  expect_same(sent, c.snapshot());
  EXPECT_EQ(s.stats().corrupt(), 0u);
  std::printf("default scene: %zu packets (%zu spike packets), %zu wire bytes\n", sent.size(),
              spikes, wire.size());
}

TEST(LinkStreamPty, CorruptAndMissingFramesAreCountedAndTheStreamGoesOn) {
  PtyPair pty;
  std::vector<Sent> sent;
  auto frames = random_frames(500, 2, sent);
  std::vector<Sent> want;
  std::vector<uint8_t> wire;
  size_t crc_bad = 0, merged = 0, left_out = 0, lost = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    auto f = frames[i];
    if (i % 50 == 10) {  // one payload byte changed, still non-zero: CRC error
      uint8_t& b = f[f.size() / 2];
      b = b == 0xFF ? 0x01 : uint8_t(b + 1);
      ++crc_bad;
      ++lost;
    } else if (i % 50 == 20 && i + 1 < frames.size()) {  // delimiter lost: merges with next
      f.pop_back();
      wire.insert(wire.end(), f.begin(), f.end());
      wire.insert(wire.end(), frames[i + 1].begin(), frames[i + 1].end());
      ++i;
      ++merged;
      lost += 2;
      continue;
    } else if (i % 50 == 30) {  // never arrives
      ++left_out;
      ++lost;
      continue;
    } else {
      want.push_back(sent[i]);
    }
    wire.insert(wire.end(), f.begin(), f.end());
    if (i % 50 == 40) wire.insert(wire.end(), {0, 0, 0});  // idle fill: no error
  }
  LinkStream s(pty_options(pty.slave_path()));
  Collector c;
  ASSERT_TRUE(pump(s, c, pty, wire, want.size()));
  // The losses after the last packet that arrives are counted once the
  // bytes behind it are decoded: wait until the counts reach what was sent
  // (an over-count still fails below), then stop the reader.
  auto reached = [&](const auto& st) {
    return st.link.crc_errors >= crc_bad && st.link.framing_errors >= merged &&
           st.link.lost_packets >= lost;
  };
  for (auto end = std::chrono::steady_clock::now() + 10s;
       !reached(s.stats()) && std::chrono::steady_clock::now() < end;)
    std::this_thread::sleep_for(5ms);
  s.stop();
  expect_same(want, c.snapshot());
  const auto st = s.stats();
  EXPECT_EQ(st.link.crc_errors, crc_bad);
  EXPECT_EQ(st.link.framing_errors, merged);
  EXPECT_EQ(st.link.payload_errors, 0u);
  EXPECT_EQ(st.link.lost_packets, lost);
  EXPECT_EQ(st.link.seq_gaps, crc_bad + merged + left_out);  // no two losses adjacent
}

TEST(LinkStreamPty, SetsStandardAndNonStandardBaudRates) {
  PtyPair pty;
  for (int baud : {3000000, 115200, 250000, 1234567}) {
    eskin::stream::Channel ch(Endpoint::serial(pty.slave_path(), baud));
    EXPECT_EQ(eskin::stream::serial_baud(ch.fd()), baud);
  }
  eskin::stream::Channel ch(Endpoint::serial(pty.slave_path(), 3000000));
  termios t{};
  ASSERT_EQ(tcgetattr(ch.fd(), &t), 0);
  EXPECT_EQ(t.c_lflag & (ICANON | ECHO | ISIG), 0u) << "raw mode";
  EXPECT_EQ(t.c_cflag & CSIZE, tcflag_t(CS8));
  EXPECT_EQ(t.c_cflag & (PARENB | CSTOPB | CRTSCTS), 0u) << "8N1 without flow control";
}

TEST(LinkStreamPty, OpenErrorsNameTheDevice) {
  try {
    eskin::stream::Channel ch(Endpoint::serial("/nonexistent/ttyUSB9"));
    FAIL() << "opened a device that does not exist";
  } catch (const eskin::stream::LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/ttyUSB9"), std::string::npos) << e.what();
  }
  try {
    eskin::stream::Channel ch(Endpoint::serial("/dev/null"));
    FAIL() << "/dev/null accepted as a serial device";
  } catch (const eskin::stream::LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("not a serial device"), std::string::npos) << e.what();
  }
  StreamOptions o = pty_options("/nonexistent/ttyUSB9");
  o.reconnect = false;
  LinkStream s(o);
  EXPECT_THROW(s.start(), eskin::stream::LinkError);
}

// A serial device vanishes (a USB adapter unplugged): the stream reports
// it, keeps retrying, and picks up the new device at the same path (a
// symlink, as a udev rule provides). A pty stands in for the device, with
// pty_hangup_ends off: a pty's hang-up otherwise ends the stream (next
// test). Packets of both sessions arrive.
TEST(LinkStreamPty, ReportsALostDeviceAndReopensIt) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("eskin_stream_reopen_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto link = dir / "board.tty";
  std::vector<Sent> sent;
  const auto frames = random_frames(200, 3, sent);

  auto board = std::make_unique<PtyPair>();
  std::filesystem::create_symlink(board->slave_path(), link);
  StreamOptions o = pty_options(link.string());
  o.pty_hangup_ends = false;
  LinkStream s(o);
  Collector c;
  c.attach(s);
  s.start();
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::Opened, 1));
  ASSERT_TRUE(write_fully(board->master(), concat({frames.begin(), frames.begin() + 100})));
  ASSERT_TRUE(c.wait_packets(100));
  board->close_master();
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::Lost, 1));
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::OpenFailed, 1)) << "retries while the board is gone";

  auto board2 = std::make_unique<PtyPair>();
  std::filesystem::remove(link);
  std::filesystem::create_symlink(board2->slave_path(), link);
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::Opened, 2));
  ASSERT_TRUE(write_fully(board2->master(), concat({frames.begin() + 100, frames.end()})));
  ASSERT_TRUE(c.wait_packets(200));
  expect_same(sent, c.snapshot());
  const auto st = s.stats();
  EXPECT_EQ(st.connects, 2u);
  EXPECT_EQ(st.disconnects, 1u);
  EXPECT_EQ(st.corrupt(), 0u);
  s.stop();
  std::filesystem::remove_all(dir);
}

// The board closes its pty (the virtual board at the end of its scene):
// a pty that hangs up never comes back (a board started again gets a new
// one), so the stream ends at once, saying so, instead of retrying; every
// packet sent before the hang-up has arrived. Through a symlink, as
// `eskin-vboard --pty-link` gives it.
TEST(LinkStreamPty, APtyThatHangsUpEndsTheStream) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("eskin_stream_hangup_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto link = dir / "board.tty";
  std::vector<Sent> sent;
  const auto frames = random_frames(100, 5, sent);
  PtyPair board;
  std::filesystem::create_symlink(board.slave_path(), link);
  LinkStream s(pty_options(link.string()));
  Collector c;
  c.attach(s);
  s.start();
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::Opened, 1));
  ASSERT_TRUE(write_fully(board.master(), concat(frames)));
  ASSERT_TRUE(c.wait_packets(sent.size()));
  board.close_master();
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::HungUp, 1)) << "the stream did not see the hang-up";
  for (auto end = std::chrono::steady_clock::now() + 5s;
       s.ended() == eskin::stream::StreamEnd::Running && std::chrono::steady_clock::now() < end;)
    std::this_thread::sleep_for(5ms);
  EXPECT_EQ(s.ended(), eskin::stream::StreamEnd::HungUp);
  std::this_thread::sleep_for(300ms);  // backoff_min_ms is 10: a retry would have come by now
  EXPECT_EQ(c.count(LinkEvent::Kind::OpenFailed), 0u) << "it retried a pty that hung up";
  EXPECT_EQ(c.count(LinkEvent::Kind::Lost), 0u);
  {
    std::lock_guard<std::mutex> lk(c.mu);
    for (const auto& e : c.events)
      if (e.kind == LinkEvent::Kind::HungUp) {
        EXPECT_NE(e.message.find("the board hung up (the virtual board's scene is over)"),
                  std::string::npos) << e.message;
        EXPECT_NE(e.message.find(link.string()), std::string::npos) << e.message;
      }
  }
  expect_same(sent, c.snapshot());
  EXPECT_EQ(s.stats().connects, 1u);
  s.stop();
  std::filesystem::remove_all(dir);
}

// An open link with nothing on it is reported idle once, and the packets'
// return is reported too.
TEST(LinkStreamPty, AnIdleLinkIsReportedOnceAndItsEnd) {
  PtyPair pty;
  StreamOptions o = pty_options(pty.slave_path());
  o.idle_after_ms = 200;
  LinkStream s(o);
  Collector c;
  c.attach(s);
  s.start();
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::Idle, 1, 3s));
  std::this_thread::sleep_for(500ms);
  EXPECT_EQ(c.count(LinkEvent::Kind::Idle), 1u) << "said more than once";
  std::vector<Sent> sent;
  ASSERT_TRUE(write_fully(pty.master(), concat(random_frames(20, 6, sent))));
  ASSERT_TRUE(c.wait_packets(sent.size()));
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::Resumed, 1));
  std::lock_guard<std::mutex> lk(c.mu);
  EXPECT_EQ(c.events[1].message, "no packets for 0.2 s: the board is idle");
  EXPECT_EQ(c.events[2].message.rfind("packets again after ", 0), 0u) << c.events[2].message;
}

// A fake board on a pty that, like a UART and like the virtual board's
// bridge, sends its frames intact only when its reader's rate (the pty's
// termios, read on the master) is the board's, and bytes that decode to
// nothing otherwise. `board_baud` 0: never intact.
class BaudFollowingBoard {
 public:
  BaudFollowingBoard(PtyPair& pty, speed_t board_baud) : pty_(pty), baud_(board_baud) {
    th_ = std::thread([this] { run(); });
  }
  ~BaudFollowingBoard() {
    stop_ = true;
    th_.join();
  }

 private:
  void run() {
    std::mt19937 rng(7);
    std::vector<Sent> sent;
    const auto frames = random_frames(200000, 8, sent);
    size_t next = 0;
    while (!stop_) {
      termios t{};
      tcgetattr(pty_.master(), &t);
      std::vector<uint8_t> chunk;
      if (baud_ != 0 && cfgetospeed(&t) == baud_) {
        for (int i = 0; i < 4; ++i) {
          const auto& f = frames[next++ % frames.size()];
          chunk.insert(chunk.end(), f.begin(), f.end());
        }
      } else {
        for (int i = 0; i < 200; ++i) chunk.push_back(uint8_t(rng()));
      }
      // Non-blocking, the rest dropped when the pty is full: once the
      // stream has ended nobody reads, and the test must still end.
      pollfd q{pty_.master(), POLLOUT, 0};
      if (::poll(&q, 1, 10) == 1 && (q.revents & POLLOUT)) {
        const int fl = fcntl(pty_.master(), F_GETFL);
        fcntl(pty_.master(), F_SETFL, fl | O_NONBLOCK);
        const ssize_t w = ::write(pty_.master(), chunk.data(), chunk.size());
        (void)w;
        fcntl(pty_.master(), F_SETFL, fl);
      }
      std::this_thread::sleep_for(2ms);
    }
  }
  PtyPair& pty_;
  speed_t baud_;
  std::atomic<bool> stop_{false};
  std::thread th_;
};

// At the wrong rate bytes arrive and nothing decodes: the stream finds it
// within the run (after baud_check_ms), probes the common rates, names the
// one that decodes, and ends.
TEST(LinkStreamPty, AWrongBaudRateIsFoundAndTheRightOneNamed) {
  PtyPair pty;
  BaudFollowingBoard board(pty, B2000000);
  StreamOptions o = pty_options(pty.slave_path());
  o.endpoint.baud = 115200;
  o.baud_check_ms = 300;
  o.probe_ms = 400;
  LinkStream s(o);
  Collector c;
  c.attach(s);
  const auto t0 = std::chrono::steady_clock::now();
  s.start();
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::WrongBaud, 1, 20s));
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 10s);
  EXPECT_EQ(s.ended(), eskin::stream::StreamEnd::WrongBaud);
  EXPECT_TRUE(c.snapshot().empty()) << "no packet at 115200 baud";
  std::lock_guard<std::mutex> lk(c.mu);
  const LinkEvent& e = c.events.back();
  EXPECT_EQ(e.attempt, 2000000);
  EXPECT_NE(e.message.find("no packet decoded at 115200 baud ("), std::string::npos) << e.message;
  EXPECT_NE(e.message.find(" framing errors in "), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("the line decodes at 2000000 baud: use --baud 2000000"),
            std::string::npos)
      << e.message;
  EXPECT_EQ(s.stats().link.frames_ok, 0u);
}

TEST(LinkStreamPty, GarbageAtEveryRateSaysNoRateDecodes) {
  PtyPair pty;
  BaudFollowingBoard board(pty, 0);
  StreamOptions o = pty_options(pty.slave_path());
  o.baud_check_ms = 300;
  o.probe_ms = 150;
  LinkStream s(o);
  Collector c;
  c.attach(s);
  s.start();
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::WrongBaud, 1, 20s));
  std::lock_guard<std::mutex> lk(c.mu);
  const LinkEvent& e = c.events.back();
  EXPECT_EQ(e.attempt, 0);
  EXPECT_NE(e.message.find("no packet decoded at 3000000 baud ("), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("no packet decoded at 2000000, 1000000, 921600, 460800, 230400, 115200 "
                           "either"),
            std::string::npos)
      << e.message;
}

TEST(LinkStreamTcp, DeliversPacketsAndReconnectsOverLoopback) {
  eskin::testing::LoopbackServer server;
  std::vector<Sent> sent;
  const auto frames = random_frames(1000, 4, sent);
  StreamOptions o;
  o.endpoint = Endpoint::parse_tcp("127.0.0.1:" + std::to_string(server.port()));
  o.backoff_min_ms = 10;
  LinkStream s(o);
  Collector c;
  c.attach(s);
  s.start();
  int conn = server.accept_one();
  ASSERT_GE(conn, 0);
  ASSERT_TRUE(write_fully(conn, concat({frames.begin(), frames.begin() + 500})));
  ASSERT_TRUE(c.wait_packets(500));
  ::close(conn);  // the server drops the connection
  ASSERT_TRUE(c.wait_event(LinkEvent::Kind::Lost, 1));
  conn = server.accept_one();
  ASSERT_GE(conn, 0);
  ASSERT_TRUE(write_fully(conn, concat({frames.begin() + 500, frames.end()})));
  ASSERT_TRUE(c.wait_packets(1000));
  EXPECT_EQ(s.stats().connects, 2u);  // before closing: then it reconnects at once
  ::close(conn);
  expect_same(sent, c.snapshot());
}

TEST(LinkStreamTcp, ParsesHostPortAndNamesErrors) {
  EXPECT_EQ(Endpoint::parse_tcp("localhost:9000").port, 9000);
  EXPECT_EQ(Endpoint::parse_tcp("[::1]:7").host, "::1");
  for (const char* bad : {"9000", "host:", "host:0", "host:70000", "host:12x", "[::1]9"})
    EXPECT_THROW(Endpoint::parse_tcp(bad), eskin::stream::LinkError) << bad;
}

}  // namespace
