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

#include "eskin/dtmf_commands.h"
#include "ucode/dtmf_engine_image.h"
#include "ucode/dtmf_top_bus.h"
#include "ucode/dtmf_ucode.h"
#include "ucode/frame_engine.h"
#include "hls/sdft_bank.h"

namespace eskin::fpga {

namespace {

// sdft_bank's arithmetic (dtmf_top: XW 12, CW 16, TW 10, FB 0); its static
// helpers do not depend on K_MAX, N or ACC_W.
using Bank = hls::SdftBank<1, 2, 12, 16, 10, 14>;

// The engine booted on the plan's microcode (configuration copied, state
// cleared, carriers to the DFT), fed frames and commands.
template <bool FAST>
class LoadRun {
  using Engine = hls::FrameEngine<hls::DtmfEngineMax<FAST>>;

 public:
  explicit LoadRun(const hls::DtmfTopPlan& p) : p_(p), im_(hls::dtmf_engine_image(p)), io_(p) {
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
    io_.on_release = [this](uint64_t) { done_ = true; };
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
      if (stream_)
        io_.frame[size_t(j)] = int32_t(hls::stream_magnitude(p_.mag_shift, int32_t(re), int32_t(im)));
      else
        io_.frame[size_t(2 * j)] = int32_t(re), io_.frame[size_t(2 * j + 1)] = int32_t(im);
    }
    io_.frame_t = io_.adc_t = t;
    io_.pending = true;
    done_ = false;
    const uint64_t start = eng_->clocks();
    uint64_t at = start;
    uint32_t pc = eng_->pc();
    run_until(limit_, [&] {
      if (pc_clocks) {  // called before each instruction: the last one is done
        (*pc_clocks)[pc] += eng_->clocks() - at;
        at = eng_->clocks(), pc = eng_->pc();
      }
      return done_;
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
  // The top's IO bus: the frame buffer, the command FIFO, an output FIFO
  // that is always empty, counters at 0, a DFT that takes carrier writes
  // at once, the neuron unit or lanes when the plan has them.
  hls::DtmfTopBus io_;
  const bool stream_ = p_.spec.datapath == hls::DtmfDatapath::Streaming;
  bool done_ = false;  // the frame was released
  uint64_t limit_ = 0;
};

// A command as cmd_decoder queues it: type, seq, len (LE), payload.
std::vector<uint8_t> queued(uint8_t type, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> b = {type, 0x5A, uint8_t(payload.size()), uint8_t(payload.size() >> 8)};
  for (uint8_t c : payload) b.push_back(c);
  return b;
}
// A command of common/eskin/dtmf_commands.h, its fields at their widths.
std::vector<uint8_t> command(dtmf_cmd::Type type, uint32_t index, uint32_t value) {
  return queued(type, dtmf_command_payload(*find_dtmf_command(type), index, value));
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
  if (p.spec.ghost && p.spec.datapath != hls::DtmfDatapath::Streaming)
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
  using namespace dtmf_cmd;
  std::vector<std::pair<std::string, std::vector<uint8_t>>> cmds = {
      {"SET_CARRIER_INC", command(kSetCarrierInc, uint32_t(k), p.inc[size_t(k)])},
      {"SET_THRESHOLD", command(kSetThreshold, 3, p.ghost.pair_tol)},
      {"SET_NEURON gain_shift", command(kSetNeuron, 0x13, uint32_t(int32_t(n1.gain_shift)))},
      {"SET_NEURON u_frac", command(kSetNeuron, 0x1C, n1.u_frac)},
      {"SET_OUTPUT_MASK", command(kSetOutputMask, 0, p.mask)},
      {"SET_DECIMATION", command(kSetDecimation, 1, p.decim_tax)},
      {"REQUEST_STATUS", command(kRequestStatus, 0, 0)},
      {"CLEAR_COUNTERS", command(kClearCounters, 0, 0)},
      {"SET_DEMIX_COEF", command(kSetDemixCoef, uint32_t(dim > 0 ? dim * dim - 1 : 0),
                                 dim > 0 ? uint16_t(p.demix.coef.back()) : 0)},
      {"rejected: type", queued(kDtmfCommandFirst - 1, {})},
      {"rejected: length", queued(kSetCarrierInc, std::vector<uint8_t>(8, 0))},
      {"rejected: index", command(kSetThreshold, 9, 0)},
      {"rejected: value", command(kSetNeuron, 0x10, 0x7FFFFFFF)},
      {"rejected: reserved bits", command(kSetOutputMask, 0, 0xE0)},
  };
  // SET_WEIGHT for each weight: its cost depends on which (its bit of
  // synapse_weights' table codes, rtl/ucode/dtmf_chain.fe sw_table).
  for (uint8_t d = 0; d < 9; ++d)
    cmds.push_back({"SET_WEIGHT " + std::to_string(d),
                    command(kSetWeight, d, uint16_t(p.synapse.w[d]))});
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
  if (p.spec.datapath == hls::DtmfDatapath::Streaming)
    load.chain_clocks = uint64_t(hls::dtmf_chain_frame_clocks(p, p.mask));
  return load;
}

}  // namespace

EngineLoad measure_engine_load(const hls::DtmfTopPlan& p, const std::vector<int32_t>& scene_x) {
  return p.spec.engine_fast_shift ? measure<true>(p, scene_x) : measure<false>(p, scene_x);
}

}  // namespace eskin::fpga
