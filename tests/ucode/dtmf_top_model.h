// A clocked model of rtl/dtmf_top.v around the frame engine's
// instruction-set model (ucode/frame_engine.h): the microcode
// rtl/ucode/dtmf_chain.fe, assembled for a plan, runs against the top's IO
// bus (ucode/dtmf_top_bus.h) with sdft_bank (hls/sdft_bank.h) and the frame
// capture at sample resolution behind it. Used by the microcode tests to compare with
// hls/dtmf_chain.h quickly; the Verilated top is compared in tests/rtl.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "hls/dtmf_chain.h"
#include "ucode/dtmf_engine_image.h"
#include "ucode/dtmf_top_bus.h"
#include "ucode/frame_engine.h"
#include "ucode/dtmf_ucode.h"

namespace dtmf_model {

struct EngineCfg {  // the UP5K build's engine (no barrel shifter)
  static constexpr int IW = 11, DW = 15, KW = 12;
  static constexpr bool FAST_SHIFT = false;
};


struct Packet {
  uint8_t type = 0;
  uint32_t t = 0;
  std::vector<uint8_t> payload;
  bool operator==(const Packet& o) const {
    return type == o.type && t == o.t && payload == o.payload;
  }
};

template <class S>
class TopModel {
 public:
  static constexpr int KS_MAX = S::K + 1;
  using Bank = eskin::hls::SdftBank<KS_MAX, S::N, 12, 16, 10, S::ACC_W>;

  TopModel(const eskin::hls::DtmfTopPlan& plan, long clk_per_sample)
      : plan_(plan), im_(eskin::hls::dtmf_engine_image(plan)), period_(clk_per_sample), io_(plan) {
    const auto words = eskin::hls::dtmf_ucode_words(im_);
    eng_ = std::make_unique<eskin::hls::FrameEngine<EngineCfg>>();
    eng_->load_program(words.data(), uint32_t(words.size()));
    eng_->load_krom(im_.krom.data(), uint32_t(im_.krom.size()));
    eng_->reset();
    io_.out = &out_;
    io_.on_release = [this](uint64_t clock) {
      max_frame_ = std::max<uint64_t>(max_frame_, clock - frame_start_);
    };
    io_.on_carriers = [this](int carriers) {  // the DFT takes the table, its window refills
      eskin::hls::SdftBankConfig<KS_MAX> c;
      c.carriers = carriers;
      for (int k = 0; k < carriers; ++k) c.inc[k] = io_.inc[size_t(k)];
      bank_.configure(c);
      refill_ = true;
    };
    // Boot until the first carrier table reaches the DFT (the ADC starts then).
    eng_->run(io_, 2000000, [this](const auto&) { return io_.adc_on; });
    check_stack();
  }

  // One ADC sample (12-bit code); the engine runs one sample period.
  void sample(uint16_t code) {
    typename Bank::Token tok[KS_MAX];
    bank_.push(int32_t(code & 0xFFFu) - 2048, tok);
    io_.adc_t = t_++;
    if (capture_frame()) {
      if (io_.pending) {
        ++io_.frame_overruns;
      } else {
        if (plan_.spec.datapath == eskin::hls::DtmfDatapath::Streaming) {
          for (int k = 0; k < plan_.ks; ++k)  // the chain's magnitudes (hls/dtmf_chain.h's)
            io_.frame[size_t(k)] = int32_t(
                eskin::hls::DtmfChain<S>::Magnitude::magnitude(tok[k].re, tok[k].im));
        } else {
          for (int k = 0; k < plan_.ks; ++k)
            io_.frame[size_t(2 * k)] = tok[k].re, io_.frame[size_t(2 * k + 1)] = tok[k].im;
        }
        if (on_frame) on_frame(io_.frame);
        io_.pending = true;
        io_.frame_t = io_.adc_t;
        frame_start_ = eng_->clocks();
      }
    }
    if (!profile_) {
      eng_->run(io_, uint64_t(period_));
      check_stack();
      return;
    }
    const uint64_t end = eng_->clocks() + uint64_t(period_);
    while (eng_->clocks() < end) {
      const uint32_t pc = eng_->pc();
      const bool waiting = eng_->in_wait();
      const uint32_t clk = eng_->step(io_, end);
      (*profile_)[waiting ? ~0u : pc] += clk;
    }
    check_stack();
  }
  // Called with each captured frame's window sums (token k's re at 2k, im
  // at 2k + 1) before the engine sees them: a test may replace them with
  // sums no ADC input gives, to reach the routines' bounds.
  std::function<void(std::vector<int32_t>& sums)> on_frame;
  // Clocks spent per instruction address (~0u: waiting), from now on.
  void profile(std::map<uint32_t, uint64_t>* p) { profile_ = p; }
  // A command frame's bytes as cmd_decoder queues them (type, seq, len, payload).
  void command(const std::vector<uint8_t>& bytes) {
    io_.cmd.insert(io_.cmd.end(), bytes.begin(), bytes.end());
  }
  // The engine's output bytes parsed as packets (type, t, len, payload).
  std::vector<Packet> packets() const {
    std::vector<Packet> v;
    const auto& b = out_;
    for (size_t i = 0; i + 7 <= b.size();) {
      Packet p;
      p.type = b[i];
      p.t = uint32_t(b[i + 1]) | uint32_t(b[i + 2]) << 8 | uint32_t(b[i + 3]) << 16 |
            uint32_t(b[i + 4]) << 24;
      const size_t n = size_t(b[i + 5]) | size_t(b[i + 6]) << 8;
      if (i + 7 + n > b.size()) break;
      p.payload = std::vector<uint8_t>(b.begin() + long(i + 7), b.begin() + long(i + 7 + n));
      v.push_back(std::move(p));
      i += 7 + n;
    }
    return v;
  }
  uint64_t max_frame_clocks() const { return max_frame_; }
  uint32_t frames_done() const { return io_.frames_done; }  // frames the engine released
  uint32_t frame_overruns() const { return io_.frame_overruns; }
  size_t sdft_loads() const { return io_.sdft_loads; }
  const eskin::hls::DtmfTopBus& bus() const { return io_; }
  const eskin::hls::EngineImage& image() const { return im_; }
  eskin::hls::FrameEngine<EngineCfg>& engine() { return *eng_; }

 private:
  // The microcode must never overflow the engine's two-entry return stack
  // (rtl/frame_engine.v asserts the same in every Verilated top): like the
  // port models' contracts, a violation throws, so every test that runs
  // the microcode here fails on it.
  void check_stack() const {
    if (eng_->stack_overflows() != 0)
      throw std::logic_error("the microcode overflowed the frame engine's return stack: the call at "
                             "PC " + std::to_string(eng_->stack_overflow_pc()) + " in clock " +
                             std::to_string(eng_->stack_overflow_clock()) +
                             " is a third nested call (" +
                             std::to_string(eng_->stack_overflows()) + " overflows)");
  }

  // hls/dtmf_chain.h's frame rule (rtl/frame_capture.v).
  bool capture_frame() {
    if (refill_) filled_ = 0, refill_ = false;
    if (filled_ < S::N) {
      if (++filled_ < S::N) return false;
      phase_ = 0;
      return true;
    }
    phase_ = phase_ + 1 == plan_.step ? 0 : phase_ + 1;
    return phase_ == 0;
  }

  eskin::hls::DtmfTopPlan plan_;
  eskin::hls::EngineImage im_;
  long period_;
  std::unique_ptr<eskin::hls::FrameEngine<EngineCfg>> eng_;
  eskin::hls::DtmfTopBus io_;  // the top's IO bus; the DFT and frame capture are below
  Bank bank_;
  bool refill_ = false;
  uint64_t frame_start_ = 0, max_frame_ = 0;
  std::vector<uint8_t> out_;
  int filled_ = 0, phase_ = 0;
  uint32_t t_ = 0;
  std::map<uint32_t, uint64_t>* profile_ = nullptr;
};

}  // namespace dtmf_model
