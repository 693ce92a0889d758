// The library and the CLI against the real FPGA design: the SystemC virtual
// board (eskin-vboard: the Verilated rtl/dtmf_top.v, the AD7476A pins, the
// USB-serial bridge on a pty) run as its own process, read through
// LinkStream exactly as a board on /dev/ttyUSB1 would be.
//
// Bounds: packets equal exactly. The board's packets equal
// hls/dtmf_chain.h's bit for bit (tests/rtl/dtmf_top_test.cpp,
// tests/vboard/), so the default scene's chain packets, framed with one seq
// per packet, are what LinkStream must deliver: same type, t and payload,
// no corrupt frame, no sequence gap. Command verdicts come from the RTL's
// cmd_decoder (docs/protocol.md §5).
#include <gtest/gtest.h>

#include <filesystem>
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
  size_t status = 0;
  for (const auto& x : got) status += x.type == eskin::link::kStatus;
  EXPECT_GE(status, 20u) << "periodic status every 1000 samples";
}

// LinkStream::command against the RTL's cmd_decoder: verdicts and reasons.
TEST(StreamOnVirtualBoard, CommandVerdictsComeFromTheFpga) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {scene_cut(0.3, "stream_vboard_cmd")});
  eskin::stream::StreamOptions opt;
  opt.endpoint = eskin::stream::Endpoint::serial(vb.pty());
  LinkStream s(opt);
  s.start();
  const auto bits = s.command("set-mask", {"0x37"});
  EXPECT_EQ(bits.ack, Ack::Rejected) << bits.message;
  EXPECT_EQ(bits.status.last_reject_reason, eskin::link::kRejectReservedBits);
  EXPECT_EQ(bits.message, "rejected: reserved mask bits set");
  const auto index = s.command("set-decimation", {"3", "10"});
  EXPECT_EQ(index.ack, Ack::Rejected) << index.message;
  EXPECT_EQ(index.status.last_reject_reason, eskin::link::kRejectBadIndex);
  const auto value = s.command("set-neuron", {"3", "99"});  // X_SHIFT: 0..31
  EXPECT_EQ(value.ack, Ack::Rejected) << value.message;
  EXPECT_EQ(value.status.last_reject_reason, eskin::link::kRejectBadValue);
  const auto ok = s.command("set-mask", {"0xD"});  // amplitudes, spikes, status
  EXPECT_EQ(ok.ack, Ack::Accepted) << ok.message;
  EXPECT_EQ(ok.status.output_mask, 0xD);
  EXPECT_EQ(ok.status.cmd_rejected, 3);
  const auto clr = s.command("clear", {});
  EXPECT_EQ(clr.ack, Ack::Accepted) << clr.message;
  EXPECT_EQ(clr.status.cmd_rejected, 0);
  // The mask took effect: no taxel packet made after the accepted command.
  const uint32_t after = ok.status.samples;
  int taxels_after = 0;
  eskin::link::Packet p;
  while (s.pop(p, 200ms))
    if (p.type == eskin::link::kTaxelsDense && p.t > after + 35) ++taxels_after;
  EXPECT_EQ(taxels_after, 0);
  s.stop();
  EXPECT_EQ(vb.wait(), 0);
}

// eskin config as a user runs it on the board's port.
TEST(StreamOnVirtualBoard, ConfigCliReportsTheFpgasRejection) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {scene_cut(0.1, "stream_vboard_cli")});
  const std::string dir = ::testing::TempDir();
  eskin::testing::Process p({ESKIN_BIN, "config", "--port", vb.pty(), "set-decimation", "0", "0"},
                            dir + "vb_cfg_out", dir + "vb_cfg_err");
  EXPECT_EQ(p.wait_exit(300s), 3) << p.out() << p.err();
  EXPECT_NE(p.out().find("rejected: value out of range"), std::string::npos) << p.out();
  EXPECT_EQ(vb.wait(), 0);
}

}  // namespace
