// The library and the CLI against the real FPGA design: the SystemC virtual
// board (eskin-vboard: the Verilated rtl/dtmf_top.v, the AD7476A pins, the
// USB-serial bridge on a pty) run as its own process, read through
// LinkStream exactly as a board on /dev/ttyUSB1 would be.
//
// Bounds: packets equal exactly. The board's packets equal
// hls/dtmf_chain.h's bit for bit (tests/rtl/dtmf_top_test.cpp,
// tests/vboard/), so the default scene's chain packets, framed with one seq
// per packet, are what LinkStream must deliver: same type, t and payload,
// no corrupt frame, no sequence gap. Command verdicts come from the RTL
// (docs/protocol.md §5): any difference from the reasons the RTL test
// expects is a bug of the board or of the host's command encoding.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <mutex>
#include <fstream>
#include <regex>
#include <thread>

#include "host/stream/link_stream.h"
#include "sim/vboard/vboard_process.h"
#include "tests/stream/frames.h"
#include "tests/stream/process.h"

namespace {

using eskin::link::Packet;
using eskin::stream::Ack;
using eskin::stream::LinkStream;
using eskin::vboard::VboardProcess;
using namespace std::chrono_literals;
const std::string kScene = ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml";

// The default scene cut to `duration_s`: the presses that end by then.
std::string scene_cut(double duration_s, const std::string& name) {
  std::ifstream in(kScene);
  std::string text, line;
  const std::regex num(R"((t_start_s|ramp_s|hold_s|release_s): ([0-9.]+))");
  while (std::getline(in, line)) {
    if (line.find("- press:") != std::string::npos) {
      double end = 0;
      for (std::sregex_iterator m(line.begin(), line.end(), num), e; m != e; ++m)
        end += std::stod((*m)[2]);
      if (end > duration_s) continue;
    }
    if (line.rfind("duration_s:", 0) == 0) line = "duration_s: " + std::to_string(duration_s);
    text += line + "\n";
  }
  const std::string path = ::testing::TempDir() + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

LinkStream::PacketFn collect(std::vector<Packet>& out, std::mutex& mu) {
  return [&out, &mu](const Packet& p) {
    std::lock_guard<std::mutex> lk(mu);
    out.push_back(p);
  };
}

// Until the board has put every byte into the pty and the stream has read them.
void wait_all_bytes(VboardProcess& vb, LinkStream& s) {
  const auto end = std::chrono::steady_clock::now() + 600s;
  while (std::chrono::steady_clock::now() < end) {
    if (vb.poll_done() && s.stats().link.bytes >= vb.done().at("bytes_to_host").get<uint64_t>())
      return;
    std::this_thread::sleep_for(10ms);
  }
  ADD_FAILURE() << "the board did not finish";
}

TEST(StreamOnVirtualBoard, DefaultSceneArrivesAsTheChainSendsIt) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {kScene});
  eskin::stream::StreamOptions opt;
  opt.endpoint = eskin::stream::Endpoint::serial(vb.pty());  // 3 Mbaud: the board's rate
  LinkStream s(opt);
  std::vector<Packet> got;
  std::mutex mu;
  s.on_packet(collect(got, mu));
  s.start();
  wait_all_bytes(vb, s);
  s.stop();
  EXPECT_EQ(vb.wait(), 0);

  std::vector<eskin::testing::Sent> want;
  eskin::testing::scene_frames(want);
  const auto st = s.stats();
  EXPECT_EQ(st.corrupt(), 0u);
  EXPECT_EQ(st.link.lost_packets, 0u);
  EXPECT_EQ(st.sync_bytes, 0u);
  // Data packets complete before the scene's end (the board pads no
  // samples: the chain's last window may close later), in order per type.
  const uint32_t n = 21000;
  for (uint8_t type : {eskin::link::kAmplitudes, eskin::link::kTaxelsDense, eskin::link::kSpikes}) {
    std::vector<const eskin::testing::Sent*> w;
    std::vector<const Packet*> g;
    for (const auto& x : want)
      if (x.type == type && (type == eskin::link::kSpikes ? x.t + 35 : x.t) < n - 35) w.push_back(&x);
    for (const auto& x : got)
      if (x.type == type && (type == eskin::link::kSpikes ? x.t + 35 : x.t) < n - 35) g.push_back(&x);
    ASSERT_GE(w.size(), 10u);
    ASSERT_EQ(g.size(), w.size()) << "type " << int(type);
    for (size_t i = 0; i < w.size(); ++i) {
      ASSERT_EQ(g[i]->t, w[i]->t) << "type " << int(type) << " #" << i;
      ASSERT_EQ(g[i]->payload, w[i]->payload) << "type " << int(type) << " #" << i;
    }
  }
  // The default build's output mask: no sparse taxels, no periodic status.
  for (const auto& x : got) {
    EXPECT_NE(x.type, eskin::link::kTaxelsSparse) << "t " << x.t;
    EXPECT_NE(x.type, eskin::link::kStatus) << "t " << x.t;
  }
}

// TAXELS_SPARSE read back against the dense packet of the same frame
// (docs/protocol.md §4): exactly the taxels with g >= max(1, threshold 0),
// row-major, same values. Returns the number of frames compared.
size_t expect_sparse_matches_dense(const std::vector<Packet>& got, uint32_t after, uint16_t thr) {
  std::map<uint32_t, const Packet*> dense;
  for (const Packet& p : got)
    if (p.type == eskin::link::kTaxelsDense && p.t > after) dense[p.t] = &p;
  size_t n = 0;
  for (const Packet& p : got) {
    if (p.type != eskin::link::kTaxelsSparse || p.t <= after) continue;
    const auto d = dense.find(p.t);
    if (d == dense.end()) continue;
    std::vector<eskin::link::SparseTaxel> want;
    for (size_t i = 0; i < d->second->taxels.size(); ++i)
      if (d->second->taxels[i] >= std::max<uint16_t>(1, thr))
        want.push_back({uint8_t(i / 3), uint8_t(i % 3), d->second->taxels[i]});
    EXPECT_EQ(p.sparse.size(), want.size()) << "t " << p.t;
    for (size_t i = 0; i < want.size() && i < p.sparse.size(); ++i) {
      EXPECT_EQ(p.sparse[i].row, want[i].row) << "t " << p.t << " #" << i;
      EXPECT_EQ(p.sparse[i].col, want[i].col) << "t " << p.t << " #" << i;
      EXPECT_EQ(p.sparse[i].value, want[i].value) << "t " << p.t << " #" << i;
    }
    ++n;
  }
  return n;
}

// LinkStream::command against the FPGA (rtl/cmd_decoder.v frames them, the
// frame engine's microcode judges them): one rejection per reason and
// command, with the reason the RTL gives (tests/rtl/dtmf_top_test.cpp
// EveryCommandIsAppliedAtRunTime), then accepted changes that take effect.
TEST(StreamOnVirtualBoard, CommandVerdictsComeFromTheFpga) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {kScene});
  eskin::stream::StreamOptions opt;
  opt.endpoint = eskin::stream::Endpoint::serial(vb.pty());
  LinkStream s(opt);
  std::vector<Packet> got;
  std::mutex mu;
  s.on_packet(collect(got, mu));
  s.start();
  using eskin::link::RejectReason;
  struct Case {
    const char* name;
    std::vector<std::string> args;
    RejectReason reason;
  };
  const Case rejected[] = {
      {"set-mask", {"0x37"}, eskin::link::kRejectReservedBits},
      {"set-decimation", {"3", "10"}, eskin::link::kRejectBadIndex},
      {"set-decimation", {"0", "0"}, eskin::link::kRejectBadValue},
      {"set-threshold", {"4", "1"}, eskin::link::kRejectBadIndex},
      {"set-neuron", {"2", "0", "0"}, eskin::link::kRejectBadIndex},    // layer 2
      {"set-neuron", {"0", "7", "41"}, eskin::link::kRejectBadValue},   // s2 > 40
      {"set-carrier", {"6", "1000"}, eskin::link::kRejectBadIndex},     // K = 6
      {"set-carrier", {"0", "0x80000000"}, eskin::link::kRejectBadValue},
      {"set-weight", {"9", "0"}, eskin::link::kRejectBadIndex},
      {"set-demix-coef", {"169", "0"}, eskin::link::kRejectBadIndex},  // (2K+1)^2 = 169
  };
  int n_rejected = 0;
  for (const Case& c : rejected) {
    const auto r = s.command(c.name, c.args);
    ++n_rejected;
    EXPECT_EQ(r.ack, Ack::Rejected) << c.name << ": " << r.message;
    EXPECT_EQ(r.status.last_reject_reason, c.reason) << c.name << ": " << r.message;
    EXPECT_EQ(r.status.last_reject_type, r.type) << c.name;
    EXPECT_EQ(r.status.last_reject_seq, r.seq) << c.name;
    EXPECT_EQ(r.status.cmd_rejected, n_rejected) << c.name;
  }
  EXPECT_EQ(s.command("set-mask", {"0x37"}).message, "rejected: reserved mask bits set");

  // Accepted: every output on, then a sparse minimum, each checked in the
  // packets made after its verdict.
  const auto all = s.command("set-mask", {"0x1F"});
  EXPECT_EQ(all.ack, Ack::Accepted) << all.message;
  EXPECT_EQ(all.status.output_mask, 0x1F);
  for (const char* name : {"set-weight", "set-neuron"}) {  // values in range: accepted
    const auto r = std::string(name) == "set-weight" ? s.command(name, {"4", "3072"})
                                                     : s.command(name, {"1", "3", "2"});
    EXPECT_EQ(r.ack, Ack::Accepted) << name << ": " << r.message;
  }
  const uint32_t all_at = all.status.samples;
  // Frames made after a verdict: wait for a few of them (board time, not ours).
  const auto wait_sparse = [&](uint32_t after, size_t n) {
    for (auto end = std::chrono::steady_clock::now() + 120s; std::chrono::steady_clock::now() < end;) {
      {
        std::lock_guard<std::mutex> lk(mu);
        size_t k = 0;
        for (const Packet& p : got) k += p.type == eskin::link::kTaxelsSparse && p.t > after + 35;
        if (k >= n) return true;
      }
      std::this_thread::sleep_for(2ms);
    }
    return false;
  };
  ASSERT_TRUE(wait_sparse(all_at, 10));
  const auto thr = s.command("set-threshold", {"0", "3000"});
  EXPECT_EQ(thr.ack, Ack::Accepted) << thr.message;
  const uint32_t thr_at = thr.status.samples;
  ASSERT_TRUE(wait_sparse(thr_at, 10));
  const auto clr = s.command("clear", {});
  EXPECT_EQ(clr.ack, Ack::Accepted) << clr.message;
  EXPECT_EQ(clr.status.cmd_rejected, 0);
  EXPECT_EQ(clr.status.cmd_accepted, 1) << "only the REQUEST_STATUS after CLEAR_COUNTERS";
  s.stop();
  EXPECT_EQ(vb.wait(), 0);

  std::lock_guard<std::mutex> lk(mu);
  // Status packets carry t + 1 = samples (docs/protocol.md §4).
  size_t statuses = 0;
  for (const Packet& p : got) {
    if (p.type != eskin::link::kStatus) continue;
    EXPECT_EQ(p.status.samples, p.t + 1);
    ++statuses;
  }
  EXPECT_GE(statuses, std::size(rejected)) << "one STATUS per rejection at least";
  // Sparse packets from the FPGA, with the default minimum, then 3000.
  std::vector<Packet> before_thr;
  for (const Packet& p : got)
    if (p.t + 35 < thr_at) before_thr.push_back(p);
  EXPECT_GE(expect_sparse_matches_dense(before_thr, all_at + 35, 0), 10u);
  EXPECT_GE(expect_sparse_matches_dense(got, thr_at + 35, 3000), 10u);
  size_t lit = 0;
  for (const Packet& p : got) lit += p.type == eskin::link::kTaxelsSparse && !p.sparse.empty();
  EXPECT_GT(lit, 0u) << "no sparse packet with a taxel on";
}

// eskin config as a user runs it on the board's port.
TEST(StreamOnVirtualBoard, ConfigCliReportsTheFpgasRejection) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {scene_cut(0.1, "stream_vboard_cli")});
  const std::string dir = ::testing::TempDir();
  // Neuron layer 0, parameter 7 (s2, 0..40): the id byte 0x07 reaches the FPGA.
  eskin::testing::Process p({ESKIN_BIN, "config", "--port", vb.pty(), "set-neuron", "0", "7", "41"},
                            dir + "vb_cfg_out", dir + "vb_cfg_err");
  EXPECT_EQ(p.wait_exit(300s), 3) << p.out() << p.err();
  EXPECT_NE(p.out().find("rejected: value out of range"), std::string::npos) << p.out();
  EXPECT_EQ(vb.wait(), 0);
}

// The number in "eskin stream: N packets; link ..." (-1: not printed).
long stream_packets(const std::string& err) {
  std::smatch m;
  if (!std::regex_search(err, m, std::regex(R"(eskin stream: (\d+) packets; link)"))) return -1;
  return std::stol(m[1]);
}

// "status: accepted N" in eskin config's report (-1: not printed).
long config_accepted(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex(R"(status: accepted (\d+))"))) return -1;
  return std::stol(m[1]);
}

// A reader closing the pty is not the end of the board, as with a USB
// serial adapter: `eskin config` twice, then `eskin stream`, one board run.
// The FPGA's command counter goes on from one config to the next (the same
// FPGA, not a new board), and the board ends at its scene's end, exit 0.
TEST(StreamOnVirtualBoard, ConfigTwiceThenStreamOnOneBoardRun) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {scene_cut(1.5, "stream_vboard_reopen")});
  const std::string dir = ::testing::TempDir();
  eskin::testing::Process c1({ESKIN_BIN, "config", "--port", vb.pty(), "set-mask", "0x1F"},
                             dir + "vb_reopen_c1_out", dir + "vb_reopen_c1_err");
  ASSERT_EQ(c1.wait_exit(120s), 0) << c1.out() << c1.err();
  eskin::testing::Process c2({ESKIN_BIN, "config", "--port", vb.pty(), "set-threshold", "0", "3000"},
                             dir + "vb_reopen_c2_out", dir + "vb_reopen_c2_err");
  ASSERT_EQ(c2.wait_exit(120s), 0) << c2.out() << c2.err();
  const long a1 = config_accepted(c1.out()), a2 = config_accepted(c2.out());
  ASSERT_GT(a1, 0) << c1.out();
  EXPECT_GT(a2, a1) << "the second config's FPGA did not count the first's commands:\n"
                    << c1.out() << c2.out();
  eskin::testing::Process st({ESKIN_BIN, "stream", "--port", vb.pty(), "-q", "--count", "20"},
                             dir + "vb_reopen_st_out", dir + "vb_reopen_st_err");
  ASSERT_EQ(st.wait_exit(120s), 0) << st.err();
  EXPECT_EQ(stream_packets(st.err()), 20) << st.err();
  EXPECT_NE(st.err().find("\"crc_errors\":0,\"framing_errors\":0"), std::string::npos) << st.err();
  EXPECT_EQ(vb.wait(), 0);
  ASSERT_FALSE(vb.done().is_null());
  EXPECT_GE(vb.done().at("reader_closes").get<uint64_t>(), 2u);
  EXPECT_EQ(vb.done().at("baud_mismatches").get<uint64_t>(), 0u);
}

// At the end of its scene the board hangs up once its reader has read
// every byte: `eskin stream` (on the board's --pty-link, as a user runs it)
// ends on its own, exit 0, with every packet the board sent (one per frame
// delimiter in the done line's frame_end_ns, with no link error), and the
// board's pty and symlink are gone.
TEST(StreamOnVirtualBoard, StreamEndsWhenTheBoardHangsUpWithEveryPacket) {
  const std::string dir = ::testing::TempDir();
  const std::string link = dir + "vb_end_board.tty";
  VboardProcess vb(ESKIN_VBOARD_BIN, {scene_cut(0.1, "stream_vboard_end"), "--pty-link", link});
  eskin::testing::Process st({ESKIN_BIN, "stream", "--port", link, "-q"}, dir + "vb_end_out",
                             dir + "vb_end_err");
  ASSERT_EQ(st.wait_exit(90s), 0) << "eskin stream did not end on its own:\n" << st.err();
  EXPECT_EQ(vb.wait(), 0);
  EXPECT_FALSE(std::filesystem::is_symlink(link)) << "the board left its --pty-link behind";
  EXPECT_FALSE(std::filesystem::exists(vb.pty())) << "the pty outlived its board";
  ASSERT_FALSE(vb.done().is_null());
  const long frames = long(vb.done().at("frame_end_ns").size());
  ASSERT_GT(frames, 100);
  EXPECT_EQ(stream_packets(st.err()), frames) << st.err();
  EXPECT_NE(st.err().find("the board hung up (the virtual board's scene is over)"),
            std::string::npos)
      << st.err();
  EXPECT_NE(st.err().find("\"crc_errors\":0,\"framing_errors\":0,\"payload_errors\":0,"
                          "\"seq_gaps\":0,\"lost_packets\":0"),
            std::string::npos)
      << st.err();
  EXPECT_EQ(vb.done().at("bytes_dropped").get<uint64_t>(), 0u);
}

// At 115200 baud the board's bridge garbles the 3 Mbaud line, as a UART
// does: eskin stream finds it within the run, probes the common rates (the
// board follows its reader's rate) and names the board's, exit 5.
TEST(StreamOnVirtualBoard, WrongBaudRateIsFoundAndTheBoardsRateNamed) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {kScene});
  const std::string dir = ::testing::TempDir();
  eskin::testing::Process st({ESKIN_BIN, "stream", "--port", vb.pty(), "--baud", "115200", "-q"},
                             dir + "vb_baud_out", dir + "vb_baud_err");
  ASSERT_EQ(st.wait_exit(90s), 5) << st.err();
  EXPECT_NE(st.err().find("no packet decoded at 115200 baud ("), std::string::npos) << st.err();
  EXPECT_NE(st.err().find("the line decodes at 3000000 baud: use --baud 3000000"),
            std::string::npos)
      << st.err();
  EXPECT_EQ(stream_packets(st.err()), 0) << st.err();
  EXPECT_EQ(vb.wait(), 0);
  EXPECT_GE(vb.done().at("baud_mismatches").get<uint64_t>(), 1u);
}

}  // namespace
