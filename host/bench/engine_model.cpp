#include "host/bench/engine_model.h"

#include <algorithm>
#include <stdexcept>

#include "ucode/dtmf_engine_image.h"
#include "ucode/dtmf_top_bus.h"
#include "ucode/dtmf_ucode.h"
#include "ucode/frame_engine.h"
#include "host/engine/exact_sdft.h"

namespace eskin::bench {
namespace {

// The UP5K build's bit-serial shifter (the benches' builds).
using Widest = hls::DtmfEngineMax<false>;

}  // namespace

struct EngineCycleModel::Impl {
  hls::DtmfTopPlan plan;
  long period;
  hls::FrameEngine<Widest> eng;
  engine::ExactSdft bank;
  hls::DtmfTopBus io;  // the top's IO bus; no commands come
  std::vector<int32_t> sums;
  bool pending_log = false;  // `log` has an entry: output bytes count for the newest frame
  uint64_t frame_start = 0, next_sample = 0;
  std::vector<FrameClocks> log;

  Impl(const hls::DtmfTopPlan& p, long per)
      : plan(p), period(per),
        bank(engine::SdftWidthsRt{p.N, 12, 16, 10, p.acc_w, 0}, p.inc), io(p) {
    const hls::EngineImage im = hls::dtmf_engine_image(p);
    const auto words = hls::dtmf_ucode_words(im);
    if (im.dend > (1 << Widest::DW) || im.krom.size() > (size_t(1) << Widest::KW))
      throw std::invalid_argument("engine model: the plan's DMEM/KROM exceed DW 15 / KW 12");
    if (p.spec.engine_fast_shift || p.spec.neuron_unit)  // clocks of another build
      throw std::invalid_argument("engine model: counts the UP5K build only: the bit-serial "
                                  "shifter, no neuron unit (engine_fast_shift and neuron_unit "
                                  "must be false)");
    eng.load_program(words.data(), uint32_t(words.size()));
    eng.load_krom(im.krom.data(), uint32_t(im.krom.size()));
    eng.reset();
    sums.assign(size_t(4 * p.ks), 0);
    // Every byte the engine writes to the output FIFO, the word port's two
    // included, counts for the open frame.
    io.on_out = [this](uint64_t clock, int bytes) {
      if (log.empty() || !pending_log) return;
      FrameClocks& f = log.back();
      if (f.first_out < 0) f.first_out = int64_t(clock - frame_start);
      f.bytes += uint32_t(bytes);
    };
    io.on_release = [this](uint64_t clock) {
      if (pending_log) log.back().done = int64_t(clock - frame_start);
    };
    // Boot until the carrier table reaches the DFT (the ADC starts then).
    eng.run(io, 2000000, [this](const auto&) { return io.adc_on; });
    if (!io.adc_on) throw std::runtime_error("engine model: the microcode never loaded the carriers");
  }

  void sample(uint16_t code) {
    const int32_t x = int32_t(code & 0xFFFu) - 2048;
    const engine::FrameClock clock{uint64_t(plan.N - 1), plan.step};
    const bool is_frame = bank.push_block(&x, 1, clock, sums.data()) == 1;
    io.adc_t = uint32_t(next_sample++);
    if (is_frame) {
      if (io.pending) {
        ++io.frame_overruns;
      } else {
        for (int k = 0; k < plan.ks; ++k)
          if (plan.spec.datapath == hls::DtmfDatapath::Streaming)  // the chain's magnitudes
            io.frame[size_t(k)] = int32_t(
                hls::stream_magnitude(plan.mag_shift, sums[size_t(k)], sums[size_t(plan.ks + k)]));
          else
            io.frame[size_t(2 * k)] = sums[size_t(k)],
                        io.frame[size_t(2 * k + 1)] = sums[size_t(plan.ks + k)];
        io.pending = pending_log = true;
        io.frame_t = io.adc_t;
        frame_start = eng.clocks();
        log.push_back({io.frame_t, -1, -1, 0});
      }
    }
    eng.run(io, uint64_t(period));
  }
};

EngineCycleModel::EngineCycleModel(const hls::DtmfTopPlan& plan, long clk_per_sample)
    : d_(std::make_unique<Impl>(plan, clk_per_sample)) {}
EngineCycleModel::~EngineCycleModel() = default;
void EngineCycleModel::sample(uint16_t code) { d_->sample(code); }
const std::vector<FrameClocks>& EngineCycleModel::frames() const { return d_->log; }
uint32_t EngineCycleModel::frame_overruns() const { return d_->io.frame_overruns; }

int64_t max_engine_clocks(const hls::DtmfTopPlan& plan, const std::vector<uint16_t>& codes,
                          long clk_per_sample) {
  EngineCycleModel m(plan, clk_per_sample);
  for (uint16_t c : codes) m.sample(c);
  int64_t worst = -1;
  for (const auto& f : m.frames()) worst = std::max(worst, f.done);
  return worst;
}

}  // namespace eskin::bench
