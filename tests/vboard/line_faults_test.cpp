// The serial line's faults (sim/vboard/line_faults.h, docs/vboard.md "Line
// faults"): the model on its own, then the real virtual board (eskin-vboard
// with the Verilated dtmf_top, its real pty read through host/stream) with
// faults each way and a pulled cable, then the eskin binary's options.
//
// The accounting that the board tests check (FPGA -> host):
//  * no delivered packet is wrong: each equals, byte for byte, the packet
//    of the fault-free run with its (seq, type, t), in the same order;
//  * every lost packet a host can see is counted by the host: its
//    lost_packets (seq gaps) equals the packets of the fault-free run it did
//    not deliver, less those before its first or after its last delivered
//    packet, which no seq number can reveal (each run of losses is far
//    below the 256 a u8 seq can tell);
//  * each injected fault (a flipped wire bit, a dropped or inserted
//    character) damages the frame it lands in and, when it spoils or fakes
//    a 0x00 delimiter or misframes the receiver across one, the frame next
//    to it: at most two packets lost per fault, and at least one error
//    frame counted per run of lost packets.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "eskin/process.h"
#include "host/link/delivery_check.h"
#include "host/link/link_encoder.h"
#include "host/stream/board_link.h"
#include "sim/vboard/line_faults.h"
#include "sim/vboard/usb_serial.h"
#include "sim/vboard/vboard_process.h"
#include "fault_harness.h"

namespace {

using fault_harness::exit_of;
using fault_harness::slurp;

namespace fs = std::filesystem;
using eskin::link::Packet;
using eskin::vboard::DirectionCounts;
using eskin::vboard::LineCounts;
using eskin::vboard::LineDir;
using eskin::vboard::LineFaultOptions;
using eskin::vboard::LineFaults;

// ---------------------------------------------------------------- the model

// A UART transmitter's level at time t for characters sent back to back
// from 0, one per 10 bits of `bit_ns`: start 0, the byte LSB first, stop 1.
bool tx_level(const std::vector<uint8_t>& bytes, double bit_ns, double t) {
  const long bit = long(t / bit_ns);
  const size_t c = size_t(bit / 10);
  if (c >= bytes.size()) return true;
  const int k = int(bit % 10);
  if (k == 0) return false;
  if (k == 9) return true;
  return (bytes[c] >> (k - 1)) & 1;
}

struct Observed {
  uint64_t start = 0, data = 0, stop = 0;
  std::vector<uint8_t> levels;  // the far end's level at each bit's middle
};

// Drives `bytes` through the line in direction d, sampling 10 times per
// bit, and reads back, at each bit's middle, which bits arrived flipped.
Observed drive(LineFaults& line, LineDir d, const std::vector<uint8_t>& bytes, double bit_ns) {
  Observed o;
  line.set_bit_ns(d, bit_ns);
  const double step = bit_ns / 10;
  const long steps = long(bytes.size()) * 100 + 50;
  for (long i = 0; i < steps; ++i) {
    const double t = double(i) * step;
    const bool in = tx_level(bytes, bit_ns, t);
    const bool out = line.wire(d, t, in);
    if (i % 10 == 5 && i / 100 < long(bytes.size())) {
      o.levels.push_back(out);
      if (out != in) {
        const int k = int((i / 10) % 10);
        ++(k == 0 ? o.start : k == 9 ? o.stop : o.data);
      }
    }
  }
  return o;
}

std::vector<uint8_t> pattern(size_t n) {
  std::vector<uint8_t> b(n);
  for (size_t i = 0; i < n; ++i) b[i] = uint8_t(i * 37 + 11);
  return b;
}

// Each wire bit flips with probability p, independently: over n bits the
// flips are Binomial(n, p); the bound is 5 standard deviations (a correct
// model fails it with probability < 1e-6).
TEST(LineModel, BitErrorsFollowTheBinomialAndAreCountedAsObserved) {
  const double p = 1e-3;
  LineFaultOptions o;
  o.to_host.ber = p;
  o.seed = 42;
  LineFaults line(o);
  const std::vector<uint8_t> bytes = pattern(200000);
  const Observed seen = drive(line, LineDir::to_host, bytes, 1000.0);
  const DirectionCounts& c = line.counts().to_host;
  EXPECT_EQ(c.chars, bytes.size());
  // What the model says it flipped is what arrived flipped, bit kind by kind.
  EXPECT_EQ(c.start_flips, seen.start);
  EXPECT_EQ(c.data_flips, seen.data);
  EXPECT_EQ(c.stop_flips, seen.stop);
  const double n = 10.0 * double(bytes.size());
  const auto within = [&](double count, double bits) {
    const double mean = bits * p, sd = std::sqrt(bits * p * (1 - p));
    EXPECT_LE(std::fabs(count - mean), 5 * sd) << count << " flips in " << bits << " bits";
  };
  within(double(seen.start + seen.data + seen.stop), n);
  within(double(seen.start), n / 10);
  within(double(seen.data), n * 0.8);
  within(double(seen.stop), n / 10);
  EXPECT_EQ(line.counts().to_fpga.flips(), 0u);  // the other direction was not asked for
}

TEST(LineModel, DropsAndInsertsFollowTheirRates) {
  const double p = 2e-3;
  LineFaultOptions o;
  o.to_fpga.drop_rate = p;
  o.to_fpga.insert_rate = p;
  LineFaults line(o);
  const int n = 500000;
  uint64_t drops = 0, inserts = 0;
  for (int i = 0; i < n; ++i) {
    const LineFaults::Fate f = line.fate(LineDir::to_fpga);
    drops += f.drop;
    inserts += f.inserted >= 0;
    EXPECT_LT(f.inserted, 256);
  }
  EXPECT_EQ(line.counts().to_fpga.dropped, drops);
  EXPECT_EQ(line.counts().to_fpga.inserted, inserts);
  const double mean = n * p, sd = std::sqrt(n * p * (1 - p));
  EXPECT_LE(std::fabs(double(drops) - mean), 5 * sd);
  EXPECT_LE(std::fabs(double(inserts) - mean), 5 * sd);
  const LineFaults::Fate none = line.fate(LineDir::to_host);  // no rate that way
  EXPECT_FALSE(none.drop);
  EXPECT_EQ(none.inserted, -1);
}

// The same seed and traffic: the same flips at the same bits, the same
// drops and inserts; another seed: other faults.
TEST(LineModel, SameSeedSameFaults) {
  const auto run = [](uint64_t seed) {
    LineFaultOptions o;
    o.to_host = {1e-3, 1e-3, 1e-3};
    o.to_fpga = {1e-3, 1e-3, 1e-3};
    o.seed = seed;
    LineFaults line(o);
    const std::vector<uint8_t> bytes = pattern(20000);
    Observed h = drive(line, LineDir::to_host, bytes, 1000.0);
    std::vector<int> fates;
    for (int i = 0; i < 20000; ++i) {
      const LineFaults::Fate f = line.fate(LineDir::to_fpga);
      fates.push_back(f.drop ? -2 : f.inserted);
    }
    return std::make_pair(h.levels, fates);
  };
  const auto a = run(7), b = run(7), c = run(8);
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
  EXPECT_NE(a.first, c.first);
  EXPECT_NE(a.second, c.second);
}

// A pulled cable: high on both sides for its whole interval whatever the
// near ends drive, the line as driven outside it; counted once.
TEST(LineModel, APulledCableBlocksBothDirections) {
  LineFaultOptions o;
  o.pulls = {{1.0, 2.0}};  // from 1 ms for 2 ms
  LineFaults line(o);
  line.set_bit_ns(LineDir::to_host, 333.3);
  line.set_bit_ns(LineDir::to_fpga, 333.3);
  uint64_t low_inside = 0, differ_outside = 0, low_outside = 0;
  for (double t = 0; t < 5e6; t += 50) {
    const bool in = (long(t / 333.3) % 3) != 0;  // lots of low bits, both ways
    const bool inside = t >= 1e6 && t < 3e6;
    for (LineDir d : {LineDir::to_host, LineDir::to_fpga}) {
      const bool out = line.wire(d, t, in);
      if (inside && !out) ++low_inside;
      if (!inside && out != in) ++differ_outside;
      if (!inside && !out) ++low_outside;
    }
  }
  EXPECT_EQ(low_inside, 0u);
  EXPECT_EQ(differ_outside, 0u);
  EXPECT_GT(low_outside, 0u);
  EXPECT_EQ(line.counts().pulls, 1u);
  EXPECT_GT(line.counts().to_host.pulled_chars, 0u);
  EXPECT_GT(line.counts().to_fpga.pulled_chars, 0u);
}

// The bridge with the line on its byte side: a dropped character never
// reaches the host, an inserted one does, before the next.
TEST(LineModel, TheBridgeDropsAndInsertsWhereTheLineSays) {
  LineFaultOptions o;
  o.to_host.drop_rate = 0.2;
  o.to_host.insert_rate = 0.2;
  LineFaults line(o), twin(o);  // twin: the same fates, drawn by the test
  eskin::vboard::UsbSerial usb;
  usb.set_baud(1e6);
  usb.set_line(&line);
  const std::vector<uint8_t> bytes = pattern(2000);
  std::vector<uint8_t> expected;
  for (uint8_t b : bytes) {
    const LineFaults::Fate f = twin.fate(LineDir::to_host);
    if (f.inserted >= 0) expected.push_back(uint8_t(f.inserted));
    if (!f.drop) expected.push_back(b);
  }
  for (double t = 0; t < 2000 * 10 * 1000.0 + 5000; t += 50)
    usb.sample_txd(t, tx_level(bytes, 1000.0, t));
  EXPECT_EQ(usb.to_host(), expected);
  EXPECT_GT(line.counts().to_host.dropped, 0u);
  EXPECT_GT(line.counts().to_host.inserted, 0u);
}

TEST(LineModel, BadOptionsNameTheOptionAndWhatItExpects) {
  using eskin::vboard::LineFaultArgs;
  using eskin::vboard::parse_line_faults;
  const auto message = [](const LineFaultArgs& a) {
    try {
      parse_line_faults(a);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  LineFaultArgs a;
  a.ber = "2";
  EXPECT_NE(message(a).find("--ber: expected a probability"), std::string::npos) << message(a);
  a.ber = "1e-5x";
  EXPECT_NE(message(a).find("--ber"), std::string::npos);
  a = {};
  a.drop_rate = "-0.1";
  EXPECT_NE(message(a).find("--drop-rate"), std::string::npos);
  a = {};
  a.insert_rate = "nan";
  EXPECT_NE(message(a).find("--insert-rate"), std::string::npos);
  a = {};
  a.pulls = {"100"};
  EXPECT_NE(message(a).find("--pull-cable: expected AT_MS:FOR_MS"), std::string::npos);
  a.pulls = {"100:0"};
  EXPECT_NE(message(a).find("--pull-cable"), std::string::npos);
  a = {};
  a.seed = "5";  // a seed with nothing to seed would not act
  EXPECT_NE(message(a).find("--fault-seed"), std::string::npos);
  a.ber = "1e-5";
  a.seed = "-5";
  EXPECT_NE(message(a).find("--fault-seed: expected an unsigned"), std::string::npos);
  a = {};
  a.direction = "to-host";
  EXPECT_NE(message(a).find("--fault-direction"), std::string::npos);
  a.ber = "1e-5";
  a.direction = "up";
  EXPECT_NE(message(a).find("--fault-direction: expected both, to-host or to-fpga"),
            std::string::npos);
  a.direction = "to-fpga";
  const LineFaultOptions ok = parse_line_faults(a);
  EXPECT_EQ(ok.to_fpga.ber, 1e-5);
  EXPECT_EQ(ok.to_host.ber, 0);
  // ... and back into the board's arguments unchanged.
  EXPECT_EQ(eskin::vboard::line_fault_args(ok),
            (std::vector<std::string>{"--ber", "1e-05", "--fault-direction",
                                      "to-fpga", "--fault-seed", "1"}));
}

// ------------------------------------------------------- the real board

const std::string kScene = ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml";

struct BoardResult {
  eskin::stream::BoardRun run;
  LineCounts injected;
  int exit = -1;
};

// The default scene on eskin-vboard, its pty read as eskin simulate reads it.
BoardResult run_board(const std::vector<std::string>& line_args,
              const std::vector<std::vector<uint8_t>>& commands = {}) {
  BoardResult r;
  eskin::vboard::VboardProcess board(ESKIN_VBOARD_BIN,
                                     eskin::stream::board_args(kScene, "", commands, line_args));
  r.run = eskin::stream::run_board(board, 3000000, commands, 1, [](const Packet&) { return -1L; });
  r.exit = board.wait();
  r.injected = eskin::vboard::line_counts_from_json(r.run.done.at("line_faults"));
  return r;
}

std::vector<uint8_t> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool same_key(const Packet& a, const Packet& b) {
  return a.seq == b.seq && a.type == b.type && a.t == b.t;
}

// Delivered against sent, payloads byte for byte, order kept.
struct Compare {
  uint64_t wrong = 0, lost = 0, loss_runs = 0, runs_then_delivered = 0;
  uint64_t unseen = 0;  // lost before the first or after the last delivered packet
  std::vector<bool> got;
};
Compare compare(const std::vector<Packet>& sent, const std::vector<Packet>& delivered) {
  Compare c;
  c.got.assign(sent.size(), false);
  size_t j = 0;
  for (const Packet& d : delivered) {
    size_t k = j;
    while (k < sent.size() && !same_key(sent[k], d)) ++k;
    if (k == sent.size() || sent[k].payload != d.payload) {
      ++c.wrong;
      ADD_FAILURE() << "delivered wrong: type " << int(d.type) << " seq " << int(d.seq) << " t "
                    << d.t;
      continue;
    }
    c.got[k] = true;
    j = k + 1;
  }
  size_t first = 0, last = sent.size();
  while (first < sent.size() && !c.got[first]) ++first;
  while (last > 0 && !c.got[last - 1]) --last;
  c.unseen = first < sent.size() ? first + (sent.size() - last) : sent.size();
  for (size_t k = 0; k < sent.size(); ++k) {
    if (c.got[k]) continue;
    ++c.lost;
    if (k == 0 || c.got[k - 1]) {
      ++c.loss_runs;
      size_t e = k;
      while (e < sent.size() && !c.got[e]) ++e;
      if (e < sent.size()) ++c.runs_then_delivered;
    }
  }
  return c;
}

// FPGA -> host: bit errors, drops and inserts. Reference: the same scene
// fault-free (the FPGA's output does not depend on the host->FPGA line,
// which is clean here; the board's tap on uart_txd must equal it too).
TEST(LineBoard, ToHostFaultsNeverDeliverAWrongPacketAndAreCounted) {
  const BoardResult ref = run_board({});
  ASSERT_EQ(ref.exit, 0);
  ASSERT_EQ(ref.run.link.crc_errors + ref.run.link.framing_errors + ref.run.link.lost_packets, 0u);
  ASSERT_GT(ref.run.rx.size(), 1000u);
  EXPECT_EQ(ref.injected.to_host.faults() + ref.injected.to_fpga.faults() + ref.injected.pulls, 0u);

  const fs::path tap = fs::path(testing::TempDir()) / "line_to_host_tap.bin";
  const BoardResult bad = run_board({"--ber", "1e-4", "--drop-rate", "1e-4", "--insert-rate", "1e-4",
                             "--fault-direction", "to-host", "--fault-seed", "7", "--tap-to-host",
                             tap.string()});
  ASSERT_EQ(bad.exit, 0);
  // The tap saw what the fault-free run delivered.
  const std::vector<eskin::link::PacketKey> tapped = eskin::link::packet_keys(read_bytes(tap));
  ASSERT_EQ(tapped.size(), ref.run.rx.size());
  for (size_t i = 0; i < tapped.size(); ++i)
    ASSERT_TRUE(tapped[i] == eskin::link::key_of(ref.run.rx[i])) << "packet " << i;

  const DirectionCounts& f = bad.injected.to_host;
  EXPECT_EQ(bad.injected.to_fpga.faults(), 0u);
  ASSERT_GE(f.faults(), 10u) << "too few faults to judge anything";
  EXPECT_GT(f.flips(), 0u);
  EXPECT_GT(f.dropped + f.inserted, 0u);
  const Compare c = compare(ref.run.rx, bad.run.rx);
  const eskin::link::DecoderStats& h = bad.run.link;
  const uint64_t errors = h.crc_errors + h.framing_errors + h.payload_errors;
  EXPECT_EQ(c.wrong, 0u);
  EXPECT_EQ(c.lost + bad.run.rx.size(), ref.run.rx.size());
  EXPECT_EQ(h.lost_packets, c.lost - c.unseen);  // the host counted every loss it can see
  EXPECT_EQ(h.seq_gaps, c.runs_then_delivered);
  EXPECT_GE(c.lost, 1u);
  EXPECT_GE(errors, c.loss_runs);             // each run of losses shows as an error frame
  EXPECT_LE(c.lost, 2 * f.faults());          // at most two packets a fault
  EXPECT_LE(errors, 2 * f.faults());
  // The library's own judgement (host/link/delivery_check.h) agrees.
  std::vector<eskin::link::PacketKey> keys;
  for (const Packet& p : bad.run.rx) keys.push_back(eskin::link::key_of(p));
  const eskin::link::DeliveryCheck dc = eskin::link::check_delivery(tapped, keys);
  EXPECT_EQ(dc.wrong, 0u);
  EXPECT_EQ(dc.lost, c.lost);
  EXPECT_EQ(dc.unseen, c.unseen);
  EXPECT_EQ(dc.recoveries, c.runs_then_delivered);
  std::printf("to-host faults %lu (flips %lu, dropped %lu, inserted %lu): %zu sent, %lu lost, "
              "%lu error frames, %lu seq gaps\n",
              (unsigned long)f.faults(), (unsigned long)f.flips(), (unsigned long)f.dropped,
              (unsigned long)f.inserted, ref.run.rx.size(), (unsigned long)c.lost,
              (unsigned long)errors, (unsigned long)h.seq_gaps);
}

// Host -> FPGA through a noisy line. Each command is SET_THRESHOLD with
// an out-of-range id: the board rejects it and answers with a STATUS
// naming its seq (last_reject_seq), so every command the FPGA judged is
// known by name. 200 of them (seq 0..199), each followed by 64 idle 0x00
// (so the replies, 120 us each on the wire, keep up with the commands).
// Checked:
//  * nothing but these commands is judged: every STATUS names one of them,
//    as SET_THRESHOLD rejected for its index; the count of rejections
//    grows by exactly one per STATUS: none judged twice, no damaged frame
//    taken for a command;
//  * replies come in the commands' order;
//  * the board counts what it dropped: at each STATUS, its crc + frame
//    errors are at least the commands sent before the one it answers that
//    were never answered (those were damaged);
//  * each injected fault spoils at most two frames (a command, or a junk
//    frame from a spoiled idle byte): crc + frame errors <= 2 x faults.
TEST(LineBoard, ToFpgaFaultsNeverApplyADamagedCommandNorOneTwice) {
  const int n = 200;
  const std::vector<std::vector<uint8_t>> cmds = fault_harness::rejected_commands(n);
  const BoardResult bad = run_board({"--ber", "1e-3", "--drop-rate", "1e-3", "--insert-rate", "1e-3",
                             "--fault-direction", "to-fpga", "--fault-seed", "11"},
                            cmds);
  ASSERT_EQ(bad.exit, 0);
  const DirectionCounts& f = bad.injected.to_fpga;
  EXPECT_EQ(bad.injected.to_host.faults(), 0u);
  EXPECT_EQ(bad.run.link.crc_errors + bad.run.link.framing_errors + bad.run.link.lost_packets, 0u);
  ASSERT_GE(f.faults(), 20u);
  std::vector<const Packet*> status;
  for (const Packet& p : bad.run.rx)
    if (p.type == eskin::link::kStatus) status.push_back(&p);
  ASSERT_FALSE(status.empty());
  std::set<int> answered;
  int prev_seq = -1, prev_rejected = 0;
  for (const Packet* p : status) {
    const eskin::link::StatusBlock& s = p->status;
    EXPECT_EQ(s.last_reject_type, eskin::link::kCmdSetThreshold);
    EXPECT_EQ(s.last_reject_reason, eskin::link::kRejectBadIndex);
    EXPECT_LT(int(s.last_reject_seq), n);
    EXPECT_GT(int(s.last_reject_seq), prev_seq) << "replies out of order or a command judged twice";
    EXPECT_EQ(int(s.cmd_rejected), prev_rejected + 1);
    EXPECT_EQ(s.cmd_accepted, 0);
    EXPECT_EQ(s.cmd_overflows, 0);
    EXPECT_EQ(s.dropped_frames, 0);
    // Commands before this one never answered: damaged, so counted.
    const int unanswered_before = int(s.last_reject_seq) - int(answered.size());
    EXPECT_GE(int(s.cmd_crc_errors + s.cmd_frame_errors), unanswered_before)
        << "at seq " << int(s.last_reject_seq);
    answered.insert(s.last_reject_seq);
    prev_seq = s.last_reject_seq;
    prev_rejected = s.cmd_rejected;
  }
  const eskin::link::StatusBlock& last = status.back()->status;
  const uint64_t board_bad = last.cmd_crc_errors + last.cmd_frame_errors;
  EXPECT_LT(answered.size(), size_t(n)) << "no command damaged: the test shows nothing";
  EXPECT_GT(answered.size(), size_t(n / 2));
  EXPECT_LE(board_bad, 2 * f.faults());
  std::printf("to-FPGA faults %lu: %d commands, %zu answered, board counted %lu crc + %lu frame "
              "errors\n",
              (unsigned long)f.faults(), n, answered.size(), (unsigned long)last.cmd_crc_errors,
              (unsigned long)last.cmd_frame_errors);
}

// The cable out while commands go to the FPGA (the same 200 rejected
// SET_THRESHOLDs, one every 76 characters, 253 us, from 10 us): those on
// the wire in the pull are never judged, the FPGA's command decoder takes
// every one after it again, each once, and the frame the pull cut is
// counted as a bad frame. Bound: the commands overlapping [10 ms, 15 ms)
// (19 or 20 at 253 us each, less the idle ones' share) plus one each side
// go unjudged. The replies on their way to the host during the pull are
// lost too (the pull blocks both ways): the host counts them as lost.
TEST(LineBoard, CommandsResumeAfterAPulledCable) {
  const int n = 200;
  const std::vector<std::vector<uint8_t>> cmds = fault_harness::rejected_commands(n);
  const BoardResult bad = run_board({"--pull-cable", "10:5"}, cmds);
  ASSERT_EQ(bad.exit, 0);
  EXPECT_EQ(bad.injected.pulls, 1u);
  EXPECT_GT(bad.injected.to_fpga.pulled_chars, 0u);
  std::vector<int> seqs;
  const Packet* last = nullptr;
  for (const Packet& p : bad.run.rx)
    if (p.type == eskin::link::kStatus) {
      seqs.push_back(p.status.last_reject_seq);
      last = &p;
    }
  ASSERT_NE(last, nullptr);
  for (size_t i = 1; i < seqs.size(); ++i) EXPECT_GT(seqs[i], seqs[i - 1]);
  const int judged = last->status.cmd_rejected;
  EXPECT_GE(n - judged, 18);
  EXPECT_LE(n - judged, 22);
  EXPECT_GE(bad.run.link.lost_packets, uint64_t(judged) - seqs.size());
  // Every command after the pull answered: the last ones are all there.
  ASSERT_GE(seqs.size(), 100u);
  for (int k = 0; k < 100; ++k) EXPECT_EQ(seqs[seqs.size() - 1 - size_t(k)], n - 1 - k);
  // The one cut in the middle is counted (a frame error or a CRC error).
  EXPECT_GE(last->status.cmd_crc_errors + last->status.cmd_frame_errors, 1);
  std::printf("pull 10 ms + 5 ms: %d of %d commands judged, %zu replies delivered\n", judged, n,
              seqs.size());
}

// The cable out for 20 ms at 200 ms, then back: nothing crosses meanwhile;
// the stream resumes by itself. Bound: every packet whose frame was
// computed (its t) more than 2 ms before the pull or after it ended is
// delivered (a frame is 1 ms; one is on the wire when the line goes, one
// when it returns); the host counts every one lost.
TEST(LineBoard, APulledCableLosesOnlyItsIntervalAndTheStreamResumes) {
  const fs::path tap = fs::path(testing::TempDir()) / "line_pull_tap.bin";
  const BoardResult bad = run_board({"--pull-cable", "200:20", "--tap-to-host", tap.string()});
  ASSERT_EQ(bad.exit, 0);
  EXPECT_EQ(bad.injected.pulls, 1u);
  EXPECT_GT(bad.injected.to_host.pulled_chars, 0u);
  EXPECT_EQ(bad.injected.to_host.faults() + bad.injected.to_fpga.faults(), 0u);
  eskin::link::LinkDecoder dec;
  std::vector<Packet> sent;
  dec.on_packet([&](const Packet& p) { sent.push_back(p); });
  dec.feed(read_bytes(tap));
  ASSERT_GT(sent.size(), 1000u);
  const Compare c = compare(sent, bad.run.rx);
  EXPECT_EQ(c.wrong, 0u);
  EXPECT_EQ(c.loss_runs, 1u);
  EXPECT_EQ(bad.run.link.seq_gaps, 1u);                // the host reports the gap ...
  EXPECT_EQ(bad.run.link.lost_packets, c.lost);        // ... and its size
  const double fs_hz = 35000;
  const double pull_from = 0.200 * fs_hz, pull_to = 0.220 * fs_hz, slack = 0.002 * fs_hz;
  uint64_t lost_in_window = 0;
  for (size_t k = 0; k < sent.size(); ++k) {
    const double t = sent[k].t;
    if (!c.got[k]) {
      EXPECT_GE(t, pull_from - slack) << "packet " << k << " lost before the pull";
      EXPECT_LE(t, pull_to + slack) << "packet " << k << " lost after the line came back";
      ++lost_in_window;
    }
  }
  // 20 ms of 3 packets a frame or so: most of them.
  EXPECT_GE(lost_in_window, 35u);
  // The first packet delivered after the gap: within the bound.
  for (size_t k = 1; k < sent.size(); ++k)
    if (c.got[k] && !c.got[k - 1]) {
      EXPECT_LE(sent[k].t, pull_to + slack);
      std::printf("pull 200 ms + 20 ms: %lu packets lost, first back at %.3f ms\n",
                  (unsigned long)c.lost, sent[k].t / fs_hz * 1e3);
    }
}

// ------------------------------------------------------------ the binaries

TEST(LineCli, BadFaultOptionsExitTwoNamingTheOption) {
  const fs::path log = fs::path(testing::TempDir()) / "line_cli.log";
  const fs::path out = fs::path(testing::TempDir()) / "line_cli_out";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--ber", "1.5"}, "--ber: expected a probability"},
      {{"--drop-rate", "abc"}, "--drop-rate: expected"},
      {{"--insert-rate", "-1"}, "--insert-rate: expected"},
      {{"--pull-cable", "10-5"}, "--pull-cable: expected AT_MS:FOR_MS"},
      {{"--fault-seed", "3"}, "--fault-seed"},
      {{"--ber", "1e-5", "--fault-direction", "sideways"}, "--fault-direction: expected"},
      {{"--pull-cable", "5000:10"}, "--pull-cable 5000:10: the scene ends at 600 ms"}};
  for (const auto& [opts, says] : cases) {
    std::vector<std::string> argv{ESKIN_BIN, "simulate", kScene, "--out", out.string()};
    argv.insert(argv.end(), opts.begin(), opts.end());
    EXPECT_EQ(exit_of(argv, log), 2) << opts[0];
    EXPECT_NE(slurp(log).find(says), std::string::npos) << slurp(log);
    std::vector<std::string> vb{ESKIN_VBOARD_BIN, kScene, "--no-wait"};
    vb.insert(vb.end(), opts.begin(), opts.end());
    if (says.find("scene ends") != std::string::npos) continue;  // eskin simulate's check
    EXPECT_EQ(exit_of(vb, log), 2) << opts[0];
    EXPECT_NE(slurp(log).find(says), std::string::npos) << slurp(log);
  }
}

// eskin simulate with a pulled cable and bit errors both ways: the line's
// table in line.json, summary.json and the report, consistent with the
// host's own counters.
TEST(LineCli, SimulateReportsTheLine) {
  const fs::path log = fs::path(testing::TempDir()) / "line_sim.log";
  const fs::path out = fs::path(testing::TempDir()) / "line_sim_out";
  fs::remove_all(out);
  ASSERT_EQ(exit_of({ESKIN_BIN, "simulate", kScene, "--out", out.string(), "--ber", "3e-5",
                     "--pull-cable", "300:10", "--fault-seed", "5"},
                    log),
            0)
      << slurp(log);
  const nlohmann::json line = nlohmann::json::parse(slurp(out / "line.json"));
  const nlohmann::json sum = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(sum.at("line"), line);
  EXPECT_EQ(line.at("packets_delivered_wrong"), 0);
  EXPECT_EQ(line.at("cable_pulls"), 1);
  EXPECT_GT(line.at("packets_lost").get<int>(), 20);
  EXPECT_EQ(line.at("host_counted_lost").get<int>(),
            line.at("packets_lost").get<int>() - line.at("packets_lost_unseen").get<int>());
  EXPECT_EQ(line.at("packets_delivered").get<int>() + line.at("packets_lost").get<int>(),
            line.at("packets_sent").get<int>());
  EXPECT_EQ(sum.at("packets"), line.at("packets_delivered"));
  EXPECT_GT(line.at("injected_to_host").at("data_flips").get<int>() +
                line.at("injected_to_host").at("start_flips").get<int>() +
                line.at("injected_to_host").at("stop_flips").get<int>(),
            0);
  const std::string html = slurp(out / "report.html");
  EXPECT_NE(html.find("line: packets sent by the FPGA"), std::string::npos);
  EXPECT_NE(slurp(log).find("line: packets sent by the FPGA"), std::string::npos);
}

}  // namespace

// ------------------------------------------------------------- the soak

namespace soak {

std::map<std::string, double> read_table(const fs::path& p) {
  std::map<std::string, double> m;
  std::ifstream in(p);
  std::string line;
  bool header = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      header = true;
      continue;
    }
    const size_t a = line.find(',');
    const size_t b = line.find(',', a + 1);
    m[line.substr(0, a)] = std::stod(line.substr(a + 1, b - a - 1));
  }
  return m;
}

// What every soak table must hold: nothing delivered wrong, every lost
// packet counted by the host, sent = delivered + lost, faults injected both
// ways at the stated BER (Binomial over the wire bits, 10 a character, 5
// standard deviations), losses and recoveries when there were faults, and
// the board counting bad command frames.
void check_table(const std::map<std::string, double>& t, double min_packets) {
  const auto at = [&](const char* k) {
    EXPECT_TRUE(t.count(k)) << k;
    return t.count(k) ? t.at(k) : -1.0;
  };
  EXPECT_GE(at("packets_sent"), min_packets);
  EXPECT_EQ(at("packets_delivered_wrong"), 0);
  EXPECT_EQ(at("packets_counted_lost"), at("packets_lost") - at("packets_lost_unseen"));
  EXPECT_EQ(at("packets_delivered") + at("packets_lost"), at("packets_sent"));
  EXPECT_GT(at("packets_lost"), 0);
  EXPECT_GT(at("recoveries"), 0);
  EXPECT_LE(at("recoveries"), at("packets_lost"));
  const double p = at("ber");
  for (const char* dir : {"to_host", "to_fpga"}) {
    const double bits = 10 * at((std::string(dir) + "_chars").c_str());
    const double flips = at((std::string(dir) + "_flips").c_str());
    EXPECT_LE(std::fabs(flips - bits * p), 5 * std::sqrt(bits * p * (1 - p)) + 1) << dir;
    EXPECT_GT(flips, 0) << dir;
  }
  // Each flip damages at most two packets (the file's header).
  EXPECT_LE(at("packets_lost"), 2 * (at("to_host_flips")));
  EXPECT_GE(at("commands_sent"), at("status_received"));
  EXPECT_GT(at("board_cmd_errors"), 0);
}

}  // namespace soak

// The soak's short form: 3.5 s of scenes/soak.yaml (> 2 10^4 packets) at
// BER 1e-5 both ways, through the real eskin binary.
TEST(LineSoak, ShortSoakDeliversNothingWrongAndCountsEveryLoss) {
  std::ifstream in(ESKIN_SOURCE_DIR "/scenes/soak.yaml");
  std::string text, line;
  while (std::getline(in, line)) {
    const size_t at = line.find("t_start_s: ");
    if (at != std::string::npos && std::stod(line.substr(at + 11)) >= 3.0) continue;
    if (line.rfind("duration_s:", 0) == 0) line = "duration_s: 3.5";
    text += line + "\n";
  }
  const fs::path scene = fs::path(testing::TempDir()) / "soak_short.yaml";
  std::ofstream(scene) << text;
  const fs::path out = fs::path(testing::TempDir()) / "soak_short_out";
  const fs::path csv = out / "soak.csv";
  const fs::path log = fs::path(testing::TempDir()) / "soak_short.log";
  fs::remove_all(out);
  fs::create_directories(out);
  ASSERT_EQ(exit_of({ESKIN_BIN, "bench", "soak", scene.string(), "--ber", "1e-5", "--fault-seed",
                     "3", "--out", out.string(), "--csv", csv.string(), "--min-packets", "20000"},
                    log),
            0)
      << slurp(log);
  soak::check_table(soak::read_table(csv), 20000);
  // The same table in the soak's report (its packets row as the CSV has it).
  const auto t = soak::read_table(csv);
  const std::string html = slurp(out / "report.html");
  EXPECT_NE(html.find("line: packets sent by the FPGA / delivered / lost / delivered wrong / "
                      "recoveries"),
            std::string::npos);
  EXPECT_NE(html.find(fmt::format("{} / {} / {} / 0 / {}", t.at("packets_sent"),
                                  t.at("packets_delivered"), t.at("packets_lost"),
                                  t.at("recoveries"))),
            std::string::npos)
      << html;
  std::printf("%s", slurp(log).c_str());
}

// docs/soak.csv, which the docs cite, holds together as a soak table does,
// over at least 10^6 packets.
TEST(LineSoak, TheDocsTableHoldsTogether) {
  soak::check_table(soak::read_table(ESKIN_SOURCE_DIR "/docs/soak.csv"), 1e6);
}
