#include "host/fpga/engine_load.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "ucode/dtmf_engine_image.h"
#include "ucode/engine_ports.h"
#include "ucode/dtmf_ucode.h"
#include "ucode/frame_engine.h"
#include "hls/sdft_bank.h"

namespace eskin::fpga {

namespace {

// The largest engine rtl/frame_engine.v builds (its DW and KW limits),
// with or without the barrel shifter (the plan's engine_fast_shift).
template <bool FAST>
struct EngineMax {
  static constexpr int IW = hls::kDtmfImemBits, DW = 15, KW = 12;
  static constexpr bool FAST_SHIFT = FAST;
};

// rtl/dtmf_top.v's IO ports as the microcode sees them: the frame buffer,
// the command FIFO, an output FIFO that is always empty (OUT_DEPTH free), counters at 0, a
// DFT that takes carrier writes at once, the neuron unit when the plan has one.
struct LoadIo {
  std::vector<int32_t> frame;
  int out_depth = 512;  // the plan's OUT_DEPTH
  bool pending = false, adc_on = false, done = false;
  uint64_t done_clock = 0;
  uint32_t t = 0;
  std::deque<uint8_t> cmd;
  int cfg_k = 0;
  bool cfg_last = false;
  hls::IzhikevichUnitPort neuron;
  hls::IzhikevichLanesPort lanes;  // the plan's neuron lanes (they take the unit's place)
  hls::OutFifoPort fifo;  // checks the word port's rule; the bytes are not kept

  uint32_t io_read(uint16_t a, uint64_t clock) {
    if (a < 0x200) return a < frame.size() ? uint32_t(frame[a]) : 0u;
    if (uint32_t d = 0; neuron.read(a, d, clock) || lanes.read(a, d, clock)) return d;
    switch (a) {
      case hls::kIoFrameT: case hls::kIoAdcT: return t;
      case hls::kIoStatus: return (pending ? 1u : 0u) | (cmd.empty() ? 0u : 2u);
      case hls::kIoCmd: return cmd.empty() ? 0u : cmd.front();
      case hls::kIoOutFree: return uint32_t(out_depth);
      default: return 0;
    }
  }
  void io_write(uint16_t a, uint32_t d, uint64_t clock) {
    if (neuron.write(a, d, clock) || lanes.write(a, d, clock) ||
        fifo.write(a, d, clock, nullptr))
      return;
    switch (a) {
      case hls::kIoFrameDone: pending = false, done = true, done_clock = clock; break;
      case hls::kIoCmdPop: if (!cmd.empty()) cmd.pop_front(); break;
      case hls::kIoSdftK: cfg_k = int(d & 0xFF), cfg_last = (d >> 8) & 1; break;
      case hls::kIoSdftInc: adc_on = adc_on || cfg_last; break;
      default: break;
    }
  }
  uint16_t events(uint64_t clock) const {
    return uint16_t((pending ? hls::kEvFramePending : 0) | (cmd.empty() ? 0 : hls::kEvCmdAvail) |
                    neuron.events(clock) | lanes.events(clock));
  }
};

// sdft_bank's arithmetic (dtmf_top: XW 12, CW 16, TW 10, FB 0); its static
// helpers do not depend on K_MAX, N or ACC_W.
using Bank = hls::SdftBank<1, 2, 12, 16, 10, 14>;

// The engine booted on the plan's microcode (configuration copied, state
// cleared, carriers to the DFT), fed frames and commands.
template <bool FAST>
class LoadRun {
  using Engine = hls::FrameEngine<EngineMax<FAST>>;

 public:
  explicit LoadRun(const hls::DtmfTopPlan& p) : p_(p), im_(hls::dtmf_engine_image(p)) {
    if (im_.dend > (1 << Engine::DW) || im_.krom.size() > (1u << Engine::KW))
      throw std::invalid_argument(fmt::format(
          "frame_engine: a {}x{} skin needs {} DMEM words and {} KROM words; the engine "
          "addresses at most {} and {}",
          p.R, p.C, im_.dend, im_.krom.size(), 1 << Engine::DW, 1u << Engine::KW));
    std::vector<uint32_t> words;
    try {
      words = hls::dtmf_ucode_words(im_);
    } catch (const std::exception& e) {
      throw std::invalid_argument(std::string("frame_engine: the microcode: ") + e.what());
    }
    eng_ = std::make_unique<Engine>();
    eng_->load_program(words.data(), uint32_t(words.size()));
    eng_->load_krom(im_.krom.data(), uint32_t(im_.krom.size()));
    eng_->reset();
    io_.frame.assign(size_t(2 * p.ks), 0);
    io_.out_depth = p.out_depth;
    io_.neuron.present = p.spec.neuron_unit && p.spec.neuron_lanes == 0;
    if (p.spec.neuron_lanes) io_.lanes.configure(p.spec.neuron_lanes, 2 * p.T, p.C);
    limit_ = 4000 * uint64_t(p.T + p.K) + 1000000;  // far above any frame, below a hang
    run_until(64 * uint64_t(im_.dend + im_.krom.size()) + 100000,
              [&] { return io_.adc_on && at_wait(); }, "its first wait");
    park();
  }

  // The frame whose newest sample is t, from samples x[t - N + 1 .. t]
  // (sample 0 is the first after the carrier load: phase 0); its clocks
  // from `pending` to the release. `pc_clocks` (2^IW long), when
  // given, gets each instruction's clocks added at its address.
  uint64_t frame(const std::vector<int32_t>& x, uint32_t t, std::vector<uint64_t>* pc_clocks = nullptr) {
    for (int j = 0; j < p_.ks; ++j) {
      int64_t re = 0, im = 0;
      for (uint32_t m = t + 1 - uint32_t(p_.N); m != t + 1; ++m) {
        const uint32_t idx = Bank::index(m * p_.inc[size_t(j)]);
        re += Bank::term(x[m], Bank::cosine(idx));
        im += Bank::term(x[m], -Bank::sine(idx));
      }
      io_.frame[size_t(2 * j)] = int32_t(re), io_.frame[size_t(2 * j + 1)] = int32_t(im);
    }
    io_.t = t;
    io_.pending = true;
    io_.done = false;
    const uint64_t start = eng_->clocks();
    uint64_t at = start;
    uint32_t pc = eng_->pc();
    run_until(limit_, [&] {
      if (pc_clocks) {  // called before each instruction: the last one is done
        (*pc_clocks)[pc] += eng_->clocks() - at;
        at = eng_->clocks(), pc = eng_->pc();
      }
      return io_.done;
    }, "the end of a frame");
    run_until(limit_, [&] { return at_wait(); }, "its wait after a frame");
    park();
    return io_.done_clock - start;
  }

  // Every taxel an active ghost site (SITE words 1), as a skin with
  // contacts everywhere would leave them: the site rule's longer paths
  // for every taxel in the next frame. Only ghost_filter writes SITE and
  // none of its paths reads it, so its clocks are those of the signal.
  void every_taxel_a_site() {
    const int64_t site = im_.symbol("SITE");
    for (int i = 0; i < p_.T; ++i) eng_->set_dmem(uint32_t(site + i), 1);
  }

  // A command frame as cmd_decoder queues it; its clocks from the end of
  // the wait to the next wait.
  uint64_t command(const std::vector<uint8_t>& bytes) {
    io_.cmd.assign(bytes.begin(), bytes.end());
    const uint64_t start = eng_->clocks();
    run_until(limit_, [&] { return at_wait() && io_.cmd.empty(); }, "its wait after a command");
    park();
    return eng_->clocks() - start;
  }

 private:
  bool at_wait() const {
    const uint32_t w = eng_->imem(eng_->pc());
    return hls::fe::cls_of(w) == hls::fe::kCtl && hls::fe::fn_of(w) == hls::fe::kWait;
  }
  // Into the wait at the next instruction (its first clock), idle there as
  // the engine is when a frame or command comes: the clocks counted from
  // then on are those after the event, as in the RTL.
  void park() {
    eng_->step(io_, eng_->clocks() + 1);
    if (!eng_->in_wait()) throw std::runtime_error("engine load: no idle wait");
  }
  // Runs until `stop`, failing (not hanging) on a microcode that never
  // gets there within `limit` clocks.
  void run_until(uint64_t limit, const std::function<bool()>& stop, const char* what) {
    eng_->run(io_, limit, [&](const Engine&) { return stop(); });
    if (!stop())
      throw std::runtime_error(fmt::format(
          "engine load: the microcode did not reach {} in {} clocks", what, limit));
  }

  const hls::DtmfTopPlan& p_;
  hls::EngineImage im_;
  std::unique_ptr<Engine> eng_;
  LoadIo io_;
  uint64_t limit_ = 0;
};

// A command as cmd_decoder queues it: type, seq, len (LE), payload.
std::vector<uint8_t> command(uint8_t type, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> b = {type, 0x5A, uint8_t(payload.size()), uint8_t(payload.size() >> 8)};
  for (uint8_t c : payload) b.push_back(c);
  return b;
}
std::vector<uint8_t> le(uint64_t v, int bytes) {
  std::vector<uint8_t> b;
  for (int i = 0; i < bytes; ++i) b.push_back(uint8_t(v >> (8 * i)));
  return b;
}
std::vector<uint8_t> cat(std::vector<uint8_t> a, const std::vector<uint8_t>& b) {
  for (uint8_t c : b) a.push_back(c);
  return a;
}

template <bool FAST>
EngineLoad measure(const hls::DtmfTopPlan& p, const std::vector<int32_t>& scene_x) {
  using LoadRun = LoadRun<FAST>;
  EngineLoad load;
  // The scene: every frame its samples make (hls/dtmf_chain.h's frame
  // rule: the first when the window is full, then every STEP samples).
  {
    LoadRun run(p);
    for (size_t t = size_t(p.N) - 1; t < scene_x.size(); t += size_t(p.step), ++load.scene_frames)
      load.scene_clocks = std::max(load.scene_clocks, run.frame(scene_x, uint32_t(t)));
  }
  // The stress signals, one after the other on one engine: carrier k at
  // level[k] of one full carrier (fixed phases), a small offset, rounded
  // and clipped as the 12-bit ADC does. Long enough for the ghost
  // filter's lookback, the packet decimations and the neurons to integrate
  // up to spiking, several times over.
  LoadRun run(p);
  const double full = p.spec.full_carrier_lsb * std::ldexp(1.0, 12 - p.spec.adc_bits);
  std::mt19937 rng(20240607);
  std::uniform_real_distribution<double> uni(0, 1.3);
  std::bernoulli_distribution coin(0.5);
  const int frames = std::max({64, 3 * p.lookback, 3 * int(p.decim_tax) + 2, 3 * int(p.decim_amp) + 2});
  // Clocks per instruction address of the longest stress frame.
  std::vector<uint64_t> pcs(size_t(1) << hls::kDtmfImemBits), worst_pcs;  // every PC the engine can hold
  using Levels = std::function<void(int, std::vector<double>&)>;
  const std::vector<std::pair<const char*, Levels>> signals = {
      {"random levels", [&](int, auto& l) { for (auto& v : l) v = uni(rng); }},
      {"random on/off", [&](int, auto& l) { for (auto& v : l) v = coin(rng) ? 1.0 : 0.0; }},
      {"all toggling every 2 frames", [&](int f, auto& l) { std::fill(l.begin(), l.end(), (f / 2) % 2 ? 0.0 : 1.0); }},
      {"steady full", [&](int, auto& l) { std::fill(l.begin(), l.end(), 1.0); }},
      {"steady quiet", [&](int, auto& l) { std::fill(l.begin(), l.end(), 0.0); }},
  };
  std::vector<double> level(size_t(p.K), 0.0);
  std::vector<int32_t> x;
  // Each signal as it comes, then (with the ghost filter) again with every
  // taxel a site before each frame: a signal alone leaves few sites, and a
  // taxel's clocks depend on whether it is one (rtl/ucode: taxel_reconstruct).
  struct Run {
    std::string name;
    const Levels* levels;
    bool sites;
  };
  std::vector<Run> runs;
  for (const auto& [name, levels] : signals) runs.push_back({name, &levels, false});
  if (p.spec.ghost)
    for (const auto& [name, levels] : signals)
      runs.push_back({std::string(name) + ", every taxel a site", &levels, true});
  // Which routine each instruction address belongs to: a frame's packets.
  const std::vector<std::string> routine = hls::dtmf_ucode_routines(hls::dtmf_engine_image(p));
  std::vector<bool> packet_pc(pcs.size(), false);
  for (size_t a = 0; a < routine.size() && a < pcs.size(); ++a)
    packet_pc[a] = routine[a] == "packets" || routine[a] == "status";
  for (const auto& [name, levels, sites] : runs) {
    uint64_t worst = 0;
    for (int f = 0; f < frames; ++f, ++load.stress_frames) {
      (*levels)(f, level);
      if (sites) run.every_taxel_a_site();
      const uint32_t t = uint32_t(p.N - 1 + load.stress_frames * p.step);
      for (uint32_t m = uint32_t(x.size()); m <= t; ++m) {
        double v = 17.0;
        for (int k = 0; k < p.K; ++k)
          v += level[size_t(k)] * full *
               std::cos(2 * M_PI * std::fmod(p.spec.carrier_hz[size_t(k)] / p.spec.sample_hz * m, 1.0) + 0.7 * k);
        x.push_back(int32_t(std::clamp(std::round(v), -2048.0, 2047.0)));
      }
      std::fill(pcs.begin(), pcs.end(), 0);
      const uint64_t clocks = run.frame(x, t, &pcs);
      uint64_t packets = 0;
      for (size_t a = 0; a < pcs.size(); ++a)
        if (packet_pc[a]) packets += pcs[a];
      load.stress_packet_clocks = std::max(load.stress_packet_clocks, packets);
      load.stress_other_clocks = std::max(load.stress_other_clocks, clocks - packets);
      if (clocks > std::max(worst, load.stress_clocks)) worst_pcs = pcs;
      worst = std::max(worst, clocks);
    }
    load.cases.emplace_back(name, worst);
    if (worst > load.stress_clocks) load.stress_clocks = worst, load.stress_case = name;
  }

  // Commands of docs/protocol.md §5 with the values the plan already has
  // (the measurement changes nothing), and each reason for a rejection.
  const int k = p.K - 1, dim = p.spec.demix ? 2 * p.K + 1 : 0;
  const auto& n1 = p.neuron[1];
  std::vector<std::pair<std::string, std::vector<uint8_t>>> cmds = {
      {"SET_CARRIER_INC", command(0x81, cat({uint8_t(k)}, le(p.inc[size_t(k)], 4)))},
      {"SET_THRESHOLD", command(0x82, cat({3}, le(p.ghost.pair_tol, 2)))},
      {"SET_NEURON gain_shift", command(0x83, cat({0x13}, le(uint32_t(int32_t(n1.gain_shift)), 4)))},
      {"SET_NEURON u_frac", command(0x83, cat({0x1C}, le(n1.u_frac, 4)))},
      {"SET_OUTPUT_MASK", command(0x84, {p.mask})},
      {"SET_DECIMATION", command(0x85, cat({1}, le(p.decim_tax, 2)))},
      {"REQUEST_STATUS", command(0x86, {})},
      {"CLEAR_COUNTERS", command(0x87, {})},
      {"SET_DEMIX_COEF", command(0x89, cat(le(dim > 0 ? dim * dim - 1 : 0, 2),
                                           le(dim > 0 ? uint16_t(p.demix.coef.back()) : 0, 2)))},
      {"rejected: type", command(0x80, {})},
      {"rejected: length", command(0x81, le(0, 8))},
      {"rejected: index", command(0x82, cat({9}, le(0, 2)))},
      {"rejected: value", command(0x83, cat({0x10}, le(0x7FFFFFFF, 4)))},
      {"rejected: reserved bits", command(0x84, {0xE0})},
  };
  // SET_WEIGHT for each weight: its cost depends on which (its bit of
  // synapse_weights' table codes, rtl/ucode/dtmf_chain.fe sw_table).
  for (uint8_t d = 0; d < 9; ++d)
    cmds.push_back({"SET_WEIGHT " + std::to_string(d),
                    command(0x88, cat({d}, le(uint16_t(p.synapse.w[d]), 2)))});
  for (const auto& [name, bytes] : cmds) {
    const uint64_t clocks = run.command(bytes);
    load.cases.emplace_back(name, clocks);
    if (clocks > load.command_clocks) load.command_clocks = clocks, load.command_case = name;
  }
  // The longest stress frame by routine, most clocks first.
  std::map<std::string, uint64_t> by;
  for (size_t a = 0; a < worst_pcs.size() && a < routine.size(); ++a)
    if (worst_pcs[a]) by[routine[a]] += worst_pcs[a];
  for (const auto& r : by) load.stress_routines.push_back(r);
  std::stable_sort(load.stress_routines.begin(), load.stress_routines.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return load;
}

}  // namespace

EngineLoad measure_engine_load(const hls::DtmfTopPlan& p, const std::vector<int32_t>& scene_x) {
  return p.spec.engine_fast_shift ? measure<true>(p, scene_x) : measure<false>(p, scene_x);
}

}  // namespace eskin::fpga
