// eskin config on a real pty. The other end answers as docs/protocol.md §5
// specifies: a rejected command bumps cmd_rejected, records type/reason/seq
// and triggers a STATUS; an accepted one bumps cmd_accepted; REQUEST_STATUS
// is accepted and sends a STATUS; CLEAR_COUNTERS zeroes the counters (and
// is not counted). Periodic STATUS packets and data packets flow meanwhile,
// as on the board. Here the verdict logic and the CLI are tested under
// control; the FPGA's own verdicts through the virtual board's pty are
// tests/stream/vboard_stream_test.cpp.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <mutex>
#include <thread>

#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "host/stream/commands.h"
#include "host/stream/link_stream.h"
#include "tests/stream/process.h"
#include "tests/stream/pty_pair.h"

namespace fs = std::filesystem;
using namespace eskin::testing;
using namespace std::chrono_literals;
using eskin::link::Packet;

namespace {

class ProtocolBoard {
 public:
  explicit ProtocolBoard(int master) : fd_(master), thread_([this] { run(); }) {}
  ~ProtocolBoard() {
    stop_ = true;
    thread_.join();
  }

 private:
  void run() {
    eskin::link::LinkDecoder dec;
    int tick = 0;
    while (!stop_) {
      const auto bytes = read_some(fd_, 5);
      dec.feed(bytes);
      Packet c;
      while (dec.pop(c)) {
        apply(c);
        heard_ = true;
      }
      if (++tick % 10 == 0) write_fully(fd_, enc_.amplitudes(samples_, {1, 2, 3, 4, 5, 6}));
      // Periodic status, once a host has spoken: the first `eskin config`
      // then always finds no status to start from and asks for one (seq 0)
      // before its command (seq 1), however slowly it starts.
      if (tick % 40 == 0 && heard_) send_status();
      samples_ += 175;
    }
  }
  void reject(const Packet& c, uint8_t reason) {
    ++st_.cmd_rejected;
    st_.last_reject_type = c.type;
    st_.last_reject_reason = reason;
    st_.last_reject_seq = c.seq;
    send_status();
  }
  void apply(const Packet& c) {
    using namespace eskin::link;
    switch (c.type) {
      case kCmdSetOutputMask:
        if (c.cmd_value & 0xE0) return reject(c, kRejectReservedBits);
        st_.output_mask = uint8_t(c.cmd_value);
        break;
      case kCmdSetDecimation:
        if (c.cmd_index >= 3) return reject(c, kRejectBadIndex);
        if (c.cmd_value == 0) return reject(c, kRejectBadValue);
        break;
      case kCmdSetThreshold:
        if (c.cmd_index >= 4) return reject(c, kRejectBadIndex);
        break;
      case kCmdSetNeuron:  // id = layer << 4 | parameter
        if (c.cmd_index >> 4 >= 2) return reject(c, kRejectBadIndex);
        {
          std::lock_guard<std::mutex> lk(mu_);
          neuron_ids_.push_back(c.cmd_index);
        }
        break;
      case kCmdRequestStatus:
        ++st_.cmd_accepted;
        return send_status();
      case kCmdClearCounters:
        st_ = StatusBlock{};
        st_.output_mask = 0xF;
        return;
      default:
        break;
    }
    ++st_.cmd_accepted;
  }
  void send_status() {
    st_.samples = samples_;
    write_fully(fd_, enc_.status(samples_, st_));
  }

 public:
  std::vector<uint8_t> neuron_ids() {  // SET_NEURON ids accepted so far
    std::lock_guard<std::mutex> lk(mu_);
    return neuron_ids_;
  }

 private:
  std::mutex mu_;
  std::vector<uint8_t> neuron_ids_;
  int fd_;
  std::atomic<bool> stop_{false};
  bool heard_ = false;  // a command came (the board thread's own)
  eskin::link::LinkEncoder enc_;
  eskin::link::StatusBlock st_ = [] {
    eskin::link::StatusBlock b;
    b.output_mask = 0xF;
    return b;
  }();
  uint32_t samples_ = 0;
  std::thread thread_;
};

struct CliRun {
  int rc;
  std::string out, err;
};

CliRun config(const std::string& port, std::vector<std::string> args) {
  const fs::path dir = fs::temp_directory_path();
  const std::string out = (dir / ("eskin_config_out_" + std::to_string(getpid()))).string();
  const std::string err = (dir / ("eskin_config_err_" + std::to_string(getpid()))).string();
  args.insert(args.begin(), {ESKIN_BIN, "config", "--port", port, "--timeout-ms", "1000"});
  Process p(args, out, err);
  const int rc = p.wait_exit(20s);
  CliRun r{rc, p.out(), p.err()};
  fs::remove(out);
  fs::remove(err);
  return r;
}

TEST(ConfigCli, AcceptedAndRejectedCommandsWithTheReasonDecoded) {
  PtyPair pty;
  ProtocolBoard board(pty.master());
  const CliRun ok = config(pty.slave_path(), {"set-mask", "0x7"});
  EXPECT_EQ(ok.rc, 0) << ok.out << ok.err;
  EXPECT_NE(ok.out.find("set-mask (type 0x84, seq 1): accepted"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("output mask 0x7"), std::string::npos) << ok.out;

  const CliRun bits = config(pty.slave_path(), {"set-mask", "0x30"});  // bit 5
  EXPECT_EQ(bits.rc, 3) << bits.out << bits.err;
  EXPECT_NE(bits.out.find("rejected: reserved mask bits set"), std::string::npos) << bits.out;

  const CliRun index = config(pty.slave_path(), {"set-decimation", "3", "10"});
  EXPECT_EQ(index.rc, 3);
  EXPECT_NE(index.out.find("rejected: index out of range"), std::string::npos) << index.out;
  const CliRun value = config(pty.slave_path(), {"set-decimation", "1", "0"});
  EXPECT_EQ(value.rc, 3);
  EXPECT_NE(value.out.find("rejected: value out of range"), std::string::npos) << value.out;

  // SET_NEURON's id byte is layer << 4 | parameter.
  const CliRun layer = config(pty.slave_path(), {"set-neuron", "2", "0", "0"});
  EXPECT_EQ(layer.rc, 3) << layer.out;
  EXPECT_NE(layer.out.find("rejected: index out of range"), std::string::npos) << layer.out;
  const CliRun neuron = config(pty.slave_path(), {"set-neuron", "1", "3", "-2"});
  EXPECT_EQ(neuron.rc, 0) << neuron.out << neuron.err;
  EXPECT_EQ(board.neuron_ids(), std::vector<uint8_t>{0x13});

  const CliRun dec = config(pty.slave_path(), {"set-decimation", "1", "70"});
  EXPECT_EQ(dec.rc, 0) << dec.out;
  const CliRun st = config(pty.slave_path(), {"status"});
  EXPECT_EQ(st.rc, 0) << st.out;
  EXPECT_NE(st.out.find("rejected 4"), std::string::npos) << st.out;
  const CliRun clr = config(pty.slave_path(), {"clear"});
  EXPECT_EQ(clr.rc, 0) << clr.out;
  EXPECT_NE(clr.out.find("accepted 1, rejected 0"), std::string::npos) << clr.out;
}

TEST(ConfigCli, NoStatusFromTheBoardIsNoVerdict) {
  PtyPair pty;  // nobody answers
  const CliRun r = config(pty.slave_path(), {"status"});
  EXPECT_EQ(r.rc, 4);
  EXPECT_NE(r.out.find("no STATUS packet from the board"), std::string::npos) << r.out;
}

TEST(ConfigCli, BadCommandsAndArgumentsAreNamed) {
  PtyPair pty;
  const CliRun unknown = config(pty.slave_path(), {"set-volume", "3"});
  EXPECT_NE(unknown.rc, 0);
  EXPECT_NE(unknown.err.find("unknown command 'set-volume'"), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("set-mask"), std::string::npos) << unknown.err;
  const CliRun wide = config(pty.slave_path(), {"set-mask", "300"});
  EXPECT_NE(wide.rc, 0);
  EXPECT_NE(wide.err.find("set-mask mask '300': expected 0..255"), std::string::npos) << wide.err;
  const CliRun count = config(pty.slave_path(), {"set-threshold", "1"});
  EXPECT_NE(count.rc, 0);
  EXPECT_NE(count.err.find("expected 2 argument(s) (id value), got 1"), std::string::npos)
      << count.err;
  const CliRun text = config(pty.slave_path(), {"set-neuron", "0", "1", "abc"});
  EXPECT_NE(text.err.find("expected an integer"), std::string::npos) << text.err;
  const CliRun layer = config(pty.slave_path(), {"set-neuron", "16", "0", "1"});
  EXPECT_NE(layer.err.find("set-neuron layer '16': expected 0..15"), std::string::npos)
      << layer.err;
}

// The library call right after start(): it waits for the link to open.
TEST(ConfigLibrary, CommandRightAfterStartWaitsForTheLink) {
  PtyPair pty;
  ProtocolBoard board(pty.master());
  eskin::stream::StreamOptions opt;
  opt.endpoint = eskin::stream::Endpoint::serial(pty.slave_path());
  eskin::stream::LinkStream s(opt);
  s.start();
  const auto r = s.command("set-threshold", {"0", "120"});
  EXPECT_EQ(r.ack, eskin::stream::Ack::Accepted) << r.message;
  const auto bad = s.command("set-threshold", {"7", "120"});
  EXPECT_EQ(bad.ack, eskin::stream::Ack::Rejected) << bad.message;
  EXPECT_EQ(bad.status.last_reject_reason, eskin::link::kRejectBadIndex);
  EXPECT_EQ(bad.status.last_reject_seq, bad.seq);
  // The board's data (an amplitude packet every ~50 ms) still flows.
  const auto amps = [&] { return s.stats().packets_by_type[eskin::link::kAmplitudes]; };
  const uint64_t before = amps();
  for (auto end = std::chrono::steady_clock::now() + 10s;
       amps() == before && std::chrono::steady_clock::now() < end;)
    std::this_thread::sleep_for(5ms);
  EXPECT_GT(amps(), before) << "no data packet after the commands";
}

// judge_reply against hand-made STATUS sequences (the rules in commands.h).
TEST(ConfigAck, JudgesStatusBlocks) {
  using eskin::stream::Ack;
  using eskin::stream::judge_reply;
  eskin::link::StatusBlock base{};
  base.cmd_accepted = 5;
  auto st = base;
  EXPECT_EQ(judge_reply(0x84, 9, base, st), Ack::Pending);  // a status from before
  st.cmd_accepted = 6;
  EXPECT_EQ(judge_reply(0x84, 9, base, st), Ack::Pending);  // only one of two counted
  st.cmd_accepted = 7;
  EXPECT_EQ(judge_reply(0x84, 9, base, st), Ack::Accepted);
  auto rej = base;
  rej.cmd_rejected = 1;
  rej.last_reject_seq = 9;
  rej.last_reject_type = 0x84;
  EXPECT_EQ(judge_reply(0x84, 9, base, rej), Ack::Rejected);
  EXPECT_EQ(judge_reply(0x84, 10, base, rej), Ack::Pending) << "someone else's rejection";
  auto sat = base;
  sat.cmd_accepted = 0xFFFF;
  EXPECT_EQ(judge_reply(0x84, 9, sat, sat), Ack::Unknown);
  eskin::link::StatusBlock cleared{};
  cleared.cmd_accepted = 1;
  EXPECT_EQ(judge_reply(0x87, 9, base, cleared), Ack::Accepted);
}

}  // namespace
