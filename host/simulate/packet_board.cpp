#include "host/simulate/packet_board.h"

#include <fmt/format.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <memory>
#include <stdexcept>

#include "eskin/skin_config.h"
#include "host/engine/dtmf_engine.h"
#include "host/engine/engine_setup.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "sim/vboard/skin_samples.h"
#include "ucode/dtmf_engine_image.h"
#include "ucode/dtmf_frame_bound.h"
#include "ucode/dtmf_top_bus.h"
#include "ucode/dtmf_ucode.h"
#include "ucode/frame_engine.h"

namespace eskin::simulate {
namespace {

// Clocks from reset until the microcode's boot hands the first carrier
// table to the DFT, which starts the ADC (rtl/dtmf_top.v); on the build's
// shifter (its clocks differ).
template <bool FAST>
uint64_t boot_clocks(const hls::DtmfTopPlan& plan) {
  const hls::EngineImage im = hls::dtmf_engine_image(plan);
  const std::vector<uint32_t> words = hls::dtmf_ucode_words(im);
  auto eng = std::make_unique<hls::FrameEngine<hls::DtmfEngineMax<FAST>>>();
  eng->load_program(words.data(), uint32_t(words.size()));
  eng->load_krom(im.krom.data(), uint32_t(im.krom.size()));
  eng->reset();
  hls::DtmfTopBus io(plan);
  eng->run(io, 2000000, [&io](const auto&) { return io.adc_on; });
  if (!io.adc_on)
    throw std::runtime_error("packet board: the microcode never loaded the carriers at boot");
  return eng->clocks();
}

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// The host's start-up commands, as the microcode would apply them between
// frames before frame 0. Only the ones a scene run sends are modelled.
struct Commands {
  uint8_t mask = 0;
  uint16_t decim[3] = {1, 1, uint16_t(hls::kDtmfStatusDecimReset)};
  uint16_t accepted = 0;
};

Commands apply_commands(const hls::DtmfTopPlan& plan,
                        const std::vector<std::vector<uint8_t>>& commands) {
  Commands c;
  c.mask = plan.mask;
  c.decim[0] = plan.decim_amp;
  c.decim[1] = plan.decim_tax;
  link::LinkDecoder dec;
  for (const auto& bytes : commands) dec.feed(bytes);
  const link::DecoderStats& st = dec.stats();
  if (st.crc_errors + st.framing_errors + st.payload_errors > 0)
    throw ConfigError("command", "the host's start-up bytes are not well-formed command frames");
  link::Packet p;
  while (dec.pop(p)) {
    if (p.type == link::kCmdSetOutputMask && p.payload.size() == 1 && (p.payload[0] & 0xE0) == 0) {
      c.mask = p.payload[0];
    } else if (p.type == link::kCmdSetDecimation && p.payload.size() == 3 && p.payload[0] < 3 &&
               (p.payload[1] | p.payload[2]) != 0) {
      c.decim[p.payload[0]] = uint16_t(p.payload[1] | p.payload[2] << 8);
    } else {
      throw ConfigError("command",
                        fmt::format("--fidelity packet models the host's SET_OUTPUT_MASK and "
                                    "SET_DECIMATION with values the FPGA accepts; command 0x{:02X} "
                                    "(payload {} bytes) needs --fidelity rtl",
                                    p.type, p.payload.size()));
    }
    ++c.accepted;
  }
  return c;
}

struct Queued {
  uint8_t type;
  uint32_t t;
  uint64_t write;  // clock it enters the FIFO
  std::vector<uint8_t> payload;
  uint64_t frame_t = 0;  // STATUS: the newest sample of the frame it follows
};

}  // namespace

PacketTiming packet_timing(const hls::DtmfTopPlan& plan) {
  PacketTiming m;
  m.clk_hz = double(plan.spec.clk_hz);
  m.period = uint64_t(std::llround(m.clk_hz / plan.spec.sample_hz));  // adc_ad7476's PERIOD
  m.adc_start =
      plan.spec.engine_fast_shift ? boot_clocks<true>(plan) : boot_clocks<false>(plan);
  m.bound = hls::dtmf_frame_bound(plan).total();
  m.byte_clocks = 10 * uint64_t(std::llround(m.clk_hz / double(plan.spec.baud)));
  m.out_depth = plan.out_depth;
  return m;
}

stream::BoardRun run_packet_board(const sim::Scene& scene, const hls::DtmfTopPlan& plan,
                                  const std::vector<std::vector<uint8_t>>& commands) {
  const Commands cmd = apply_commands(plan, commands);
  const PacketTiming tm = packet_timing(plan);

  // The ADC's codes as the Verilated board's (the same tail).
  const vboard::SkinSamples bc = vboard::skin_samples(scene, 12 - plan.spec.adc_bits, vboard::kSkinTailS);
  const uint64_t samples = bc.samples;
  const size_t scene_samples = bc.scene_samples;
  // The board's work from here, as the Verilated board counts its own
  // from its first clock: the model set up and the scene's samples made.
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = thread_cpu_s();

  engine::EngineConfig ec = engine::engine_config(plan);
  ec.mask = cmd.mask;
  ec.decim_amp = cmd.decim[0];
  ec.decim_tax = cmd.decim[1];
  const engine::DtmfEngine eng(ec);
  const engine::PacketStream ps = eng.run(bc.codes.data(), size_t(samples));

  // The frame each packet is written in (a spike window's packet: the
  // window's last frame), and the periodic STATUS after a frame's packets.
  const uint64_t step = uint64_t(plan.step), first = uint64_t(plan.N - 1);
  const bool status_on = (cmd.mask & hls::kMaskStatus) != 0;
  std::vector<Queued> q;
  q.reserve(ps.packets.size() + 16);
  uint64_t next_status = first;  // frame 0, then every decim[2] frames
  const auto status_until = [&](uint64_t frame_t) {
    for (; status_on && next_status <= frame_t; next_status += step * cmd.decim[2]) {
      Queued s{link::kStatus, 0, tm.write_clock(next_status), {}, next_status};
      // t: the ADC's newest sample when the block is read (samples taken - 1).
      s.t = uint32_t((s.write - tm.adc_start) / tm.period);
      q.push_back(std::move(s));
    }
  };
  for (const engine::EnginePacket& p : ps.packets) {
    const uint64_t frame_t =
        p.type == hls::kDtmfSpikes ? p.t + (uint64_t(cmd.decim[1]) - 1) * step : p.t;
    status_until(frame_t - 1);  // the status of earlier frames first
    const uint8_t* b = ps.payload(p);
    q.push_back({p.type, p.t, tm.write_clock(frame_t), std::vector<uint8_t>(b, b + p.len)});
  }
  if (ps.frames > 0) status_until(first + (ps.frames - 1) * step);
  std::stable_sort(q.begin(), q.end(),
                   [](const Queued& a, const Queued& b) { return a.write < b.write; });

  // Spike events dropped up to a STATUS's frame (newest sample frame_t): the
  // engine over that prefix of the recording (only when any were dropped).
  const auto spikes_dropped_by = [&](uint64_t frame_t) -> uint16_t {
    if (ps.spikes_dropped == 0) return 0;
    return uint16_t(eng.run(bc.codes.data(), size_t(frame_t + 1)).spikes_dropped);
  };

  // FIFO and UART, packet by packet; the run ends when the ADC has taken
  // its last sample, as the Verilated board's does.
  const uint64_t end = tm.adc_start + (samples - 1) * tm.period + 1;
  link::LinkEncoder enc;
  std::deque<std::pair<uint64_t, int>> fifo;  // (clock its first byte leaves, FIFO bytes)
  int level = 0;
  uint64_t wire_free = 0, dropped = 0;
  std::vector<uint8_t> wire;
  std::vector<double> ends_ns;
  for (Queued& p : q) {
    while (!fifo.empty() && fifo.front().first <= p.write) {
      level -= fifo.front().second;
      fifo.pop_front();
    }
    if (p.write >= end) break;
    const int raw = 7 + int(p.type == link::kStatus ? link::kStatusBytes : p.payload.size());
    if (level + raw > tm.out_depth) {
      ++dropped;
      continue;
    }
    std::vector<uint8_t> frame;
    if (p.type == link::kStatus) {
      link::StatusBlock s;
      s.cmd_accepted = cmd.accepted;
      s.output_mask = cmd.mask;
      s.dropped_frames = uint16_t(std::min<uint64_t>(dropped, 0xFFFF));
      s.spikes_dropped = spikes_dropped_by(p.frame_t);
      s.samples = p.t + 1;
      frame = enc.status(p.t, s);
    } else {
      frame = enc.frame(p.type, p.t, p.payload);
    }
    const uint64_t start = std::max(p.write, wire_free);
    fifo.emplace_back(start, raw);
    level += raw;
    wire_free = start + frame.size() * tm.byte_clocks;
    if (wire_free > end) {  // cut by the end of the run: the bytes out so far
      wire.insert(wire.end(), frame.begin(), frame.begin() + long((end - start) / tm.byte_clocks));
      break;
    }
    wire.insert(wire.end(), frame.begin(), frame.end());
    ends_ns.push_back(tm.ns(wire_free));
  }

  // The host's side: the bytes through the host's own decoder.
  stream::BoardRun run;
  link::LinkDecoder dec;
  dec.on_packet([&run](const link::Packet& p) { run.rx.push_back(p); });
  dec.feed(wire);
  run.link = dec.stats();
  run.timed = ends_ns.size() == run.rx.size();
  run.arrival_us.assign(run.rx.size(), -1.0);
  if (run.timed)
    for (size_t i = 0; i < run.rx.size(); ++i) run.arrival_us[i] = ends_ns[i] / 1000.0;
  run.done = {{"event", "done"},
              {"fidelity", "packet"},
              {"cycles", end},
              {"sim_s", double(end) / tm.clk_hz},
              {"cpu_s", thread_cpu_s() - cpu0},
              {"wall_s",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count()},
              {"samples", samples},
              {"scene_samples", scene_samples},
              {"bytes_to_host", wire.size()},
              {"frame_end_ns", ends_ns},
              {"model_dropped_packets", dropped},
              {"arrival_bound_ns", tm.ns(tm.max_error_clocks())}};
  return run;
}

}  // namespace eskin::simulate
