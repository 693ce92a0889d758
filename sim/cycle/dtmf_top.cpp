#include "sim/cycle/dtmf_top.h"

#include <algorithm>
#include <deque>
#include <stdexcept>
#include <vector>

#include "sim/cycle/adc_ad7476.h"
#include "sim/cycle/byte_fifo.h"
#include "sim/cycle/cmd_decoder.h"
#include "sim/cycle/frame_capture.h"
#include "sim/cycle/link_framer.h"
#include "sim/cycle/sdft_bank.h"
#include "sim/cycle/uart_rx.h"
#include "sim/cycle/uart_tx.h"
#include "ucode/dtmf_engine_image.h"
#include "ucode/dtmf_io_map.h"
#include "ucode/dtmf_ucode.h"
#include "ucode/engine_ports.h"
#include "ucode/frame_engine.h"

namespace eskin::cycle {

namespace {

// The 12-bit code as the DFT takes it: code - 2048, sign in bit 11.
int32_t centred(uint16_t code) { return int32_t(code & 0x0FFFu) - 2048; }

}  // namespace

std::string DtmfTop::unsupported(const hls::DtmfTopPlan& p) {
  const hls::DtmfTopSpec& s = p.spec;
  if (s.datapath != hls::DtmfDatapath::FrameEngine) return "STREAM: the streaming datapath";
  if (s.sdft_lanes != 1) return "SDFT_LANES " + std::to_string(s.sdft_lanes) + ": more than one DFT lane";
  if (s.sdft_fifo != 0) return "SDFT_FIFO " + std::to_string(s.sdft_fifo) + ": a sample FIFO";
  if (s.adc_clk_hz != 0) return "ADC_CLK_HZ: the ADC on a clock of its own";
  if (s.neuron_lanes != 0) return "NEURON_LANES " + std::to_string(s.neuron_lanes) + ": the neuron unit's lanes";
  try {
    const AdcAd7476 adc(s.clk_hz, std::llround(s.sample_hz), int(hls::dtmf_top_sclk_div(s.clk_hz)));
    if (adc.lag() != 0) return "CLK_HZ " + std::to_string(s.clk_hz) + ": the ADC's SDATA taken at a falling edge";
  } catch (const std::invalid_argument& e) {
    return std::string("CLK_HZ / SAMPLE_HZ: ") + e.what();
  }
  return "";
}

class DtmfTop::Impl {
 public:
  virtual ~Impl() = default;
  virtual vboard::FpgaOutputs cycle(const vboard::FpgaInputs& in) = 0;
  virtual uint64_t clocks() const = 0;
  std::vector<uint64_t> carrier_loads;
};

namespace {

template <bool FAST>
class Top final : public DtmfTop::Impl {
  using Engine = hls::FrameEngine<hls::DtmfEngineMax<FAST>>;

 public:
  explicit Top(const hls::DtmfTopPlan& p)
      : adc_(p.spec.clk_hz, std::llround(p.spec.sample_hz), int(hls::dtmf_top_sclk_div(p.spec.clk_hz))),
        sdft_(p.ks, p.N, p.acc_w),
        cap_(p.ks, p.acc_w, p.N, p.step),
        rx_(uint64_t(p.spec.clk_hz), uint64_t(p.spec.baud)),
        cmd_(512),
        out_(p.out_depth),
        tx_(uint64_t(p.spec.clk_hz), uint64_t(p.spec.baud)),
        eng_(std::make_unique<Engine>()),
        io_{this},
        unit_present_(p.spec.neuron_unit) {
    const hls::EngineImage im = hls::dtmf_engine_image(p);
    const std::vector<uint32_t> words = hls::dtmf_ucode_words(im);
    eng_->load_program(words.data(), uint32_t(words.size()));
    eng_->load_krom(im.krom.data(), uint32_t(im.krom.size()));
    reset_blocks();
    reset_unit();
  }

  uint64_t clocks() const override { return now_; }

  vboard::FpgaOutputs cycle(const vboard::FpgaInputs& in) override {
    const uint64_t T = known_;  // this call gives clock T's inputs
    if (known_ - now_ >= kInputs) throw std::logic_error("cycle::DtmfTop: inputs ahead of the top");
    inputs_[known_ % kInputs] = Pins{in.reset, in.adc_sdata, in.uart_rxd};
    ++known_;
    // The engine: once out of reset, every instruction whose bus accesses
    // fall in clocks whose inputs are known (its cycle A at clocks - 1 or
    // clocks, a read there; T + 1 at the latest).
    for (;;) {
      if (!running_) {
        if (now_ > T + 1) break;
        if (!por_rst_) {  // the first clock out of reset: the engine's clock 0
          running_ = true;
          r0_ = now_;
          eng_->reset();
          reset_unit();  // its clocks are the engine's, from 0 again
          continue;
        }
        if (now_ == T + 1) break;
        edge();
        continue;
      }
      if (r0_ + eng_->clocks() > T + 1) break;
      eng_->step(io_, T + 2 - r0_);
      if (!running_) continue;  // a reset came while it ran
    }
    while (now_ < T + 1) edge();
    vboard::FpgaOutputs o;
    o.adc_cs_n = adc_.cs_n();
    o.adc_sclk = adc_.sclk();
    o.uart_txd = tx_.tx();
    return o;
  }

  // The engine's bus (ucode/frame_engine.h's IO object).
  struct Bus {
    Top* top;
    uint32_t io_read(uint16_t a, uint64_t clock) { return top->read(a, top->r0_ + clock); }
    void io_write(uint16_t a, uint32_t d, uint64_t clock) { top->write(a, d, top->r0_ + clock); }
    uint16_t events(uint64_t clock) { return top->events(top->r0_ + clock); }
  };

 private:
  struct Write {
    uint64_t clock;
    uint16_t addr;
    uint32_t data;
  };

  void reset_blocks() {
    adc_.reset();
    sdft_.reset();
    cap_.reset();
    rx_.reset();
    cmd_.reset();
    out_.reset();
    fr_.reset();
    tx_.reset();
    cfg_k_ = 0;
    cfg_last_ = cfg_valid_ = false;
    cfg_inc_ = 0;
    adc_en_ = false;
    rx_errors_ = 0;
    word_held_ = false;
  }

  // The unit's port as after a reset: no update in flight (its constant
  // words stay: the boot writes them again).
  void reset_unit() {
    uint32_t cfg[32];
    std::copy(std::begin(unit_.cfg), std::end(unit_.cfg), cfg);
    unit_ = hls::IzhikevichUnitPort{};
    unit_.present = unit_present_;
    std::copy(std::begin(cfg), std::end(cfg), unit_.cfg);
  }

  void advance_to(uint64_t c) {
    if (c < now_) throw std::logic_error("cycle::DtmfTop: the engine accessed a clock already past");
    while (now_ < c) edge();
  }

  // The value rtl/dtmf_top.v's read register takes at clock c's edge for
  // address a (the frame buffer when bit 9 is clear, else a register by
  // bits 3:0).
  uint32_t read(uint16_t a, uint64_t c) {
    if (!running_) return 0;  // a reset came in the middle of this instruction
    advance_to(c);
    if (!(a & 0x200)) return cap_.read_now(uint8_t(a & 0xFF));
    if (uint32_t d = 0; unit_.read(a, d, c - r0_)) return d;
    switch (a & 0xF) {
      case hls::kIoFrameT & 0xF: return cap_.frame_t();
      case hls::kIoStatus & 0xF: return (cmd_.avail() ? 2u : 0u) | (cap_.pending() ? 1u : 0u);
      case hls::kIoCmd & 0xF: return cmd_.head();
      case hls::kIoOutFree & 0xF: return out_.free();
      case hls::kIoAdcT & 0xF: return adc_.m_t();
      case hls::kIoAdcOvr & 0xF: return adc_.overruns();
      case hls::kIoRxErr & 0xF: return rx_errors_;
      case hls::kIoCrcErr & 0xF: return cmd_.crc_errors();
      case hls::kIoFrmErr & 0xF: return cmd_.frame_errors();
      case hls::kIoFrameOvr & 0xF: return cap_.overruns();
      case hls::kIoSdftBusy & 0xF: return cfg_valid_ ? 1u : 0u;
      case hls::kIoCmdOvf & 0xF: return cmd_.overflows();
      default: return 0;  // IO_IZ_EVN: the lanes' events, none in this build
    }
  }
  void write(uint16_t a, uint32_t d, uint64_t c) {
    if (!running_) return;  // the engine was reset: it writes nothing
    if (c < now_) throw std::logic_error("cycle::DtmfTop: the engine wrote in a clock already past");
    if (unit_.write(a, d, c - r0_)) return;  // the unit's port keeps its own clocks
    writes_.push_back({c, a, d});
  }
  uint16_t events(uint64_t c) {
    if (!running_) return 0;
    advance_to(c);
    return uint16_t((cap_.pending() ? hls::kEvFramePending : 0) | (cmd_.avail() ? hls::kEvCmdAvail : 0) |
                    unit_.events(c - r0_));
  }

  // Clock now_'s edge: every block with this clock's inputs (the board's,
  // the engine's write) and the registers as they were before it.
  void edge() {
    const Pins in = inputs_[now_ % kInputs];
    // The engine's write in this clock, if any.
    bool we = false;
    uint16_t wa = 0;
    uint32_t wd = 0;
    if (!writes_.empty() && writes_.front().clock == now_) {
      we = true, wa = writes_.front().addr, wd = writes_.front().data;
      writes_.pop_front();
    }
    const bool rst = por_rst_;
    const bool wr_out = we && wa == hls::kIoOutByte, wr_word = we && wa == hls::kIoOutWord;
    const bool wr_done = we && wa == hls::kIoFrameDone, wr_pop = we && wa == hls::kIoCmdPop;
    const bool wr_sdk = we && wa == hls::kIoSdftK, wr_sdinc = we && wa == hls::kIoSdftInc;
    const bool wr_clear = we && wa == hls::kIoClear;

    // Combinational values from the registers before the edge.
    const bool sd_in_ready = sdft_.in_ready(cfg_valid_);
    const bool cfg_ready = sdft_.cfg_ready();
    const bool cfg_done = cfg_valid_ && cfg_ready && cfg_last_;
    const bool adc_valid = adc_.m_valid();
    const int32_t adc_x = centred(adc_.m_code());
    const uint32_t adc_t = adc_.m_t();
    const bool fire = adc_valid && sd_in_ready;
    const bool skip = !cap_.smp_frame();
    const bool tok_valid = sdft_.out_valid(), tok_last = sdft_.out_last();
    const int32_t tok_re = sdft_.out_re(), tok_im = sdft_.out_im();
    const bool rx_valid = rx_.m_valid(), rx_err = rx_.frame_err() || rx_.overrun();
    const uint8_t rx_data = rx_.m_data();
    const bool fifo_in = wr_out || wr_word || word_held_;
    const uint8_t fifo_byte = word_held_ ? word_hi_ : uint8_t(wd & 0xFF);
    const bool eo_valid = out_.out_valid();
    const uint8_t eo_data = out_.out_data();
    const bool fr_s_ready = fr_.s_ready();
    const bool fr_valid = fr_.m_valid();
    const uint8_t fr_data = fr_.m_data();
    const bool tx_ready = tx_.s_ready();

    if (rst) {
      reset_blocks();
      if (running_) {  // the engine is held in reset too: its run so far ends here
        running_ = false;
        writes_.clear();
      }
    } else {
      adc_.clock(adc_en_, in.adc_sdata ? 1u : 0u, sd_in_ready, wr_clear);
      sdft_.clock(adc_valid, adc_x, skip, cfg_valid_, cfg_k_, cfg_inc_, cfg_last_, true);
      cap_.clock(cfg_done, fire, adc_t, tok_valid, tok_last, tok_re, tok_im, 0, wr_done, wr_clear);
      if (wr_clear) rx_errors_ = 0;
      else if (rx_err && rx_errors_ != 0xFFFF) ++rx_errors_;
      rx_.clock(in.uart_rxd, true);
      cmd_.clock(rx_valid, rx_data, rx_err, wr_pop, wr_clear);
      out_.clock(fifo_in, fifo_byte, fr_s_ready);
      fr_.clock(eo_valid, eo_data, tx_ready);
      tx_.clock(fr_valid, fr_data);
      if (wr_word) word_hi_ = uint8_t(wd >> 8);
      word_held_ = wr_word;
      if (wr_sdk) cfg_last_ = (wd >> 8) & 1, cfg_k_ = uint8_t(wd & 0xFF);
      if (wr_sdinc) {
        cfg_inc_ = wd;
        cfg_valid_ = true;
      } else if (cfg_ready) {
        cfg_valid_ = false;
      }
      if (cfg_done) {
        adc_en_ = true;
        carrier_loads.push_back(now_);
      }
    }
    // power_on_reset: 16 clocks from configuration, and the button
    // (rst_n low) through two flops and 15 clocks more.
    const bool sync1 = rst_sync_[1];
    rst_sync_[1] = rst_sync_[0];
    rst_sync_[0] = !in.reset;
    const int por = por_cnt_;
    if (!sync1) por_cnt_ = 0;
    else if (por_cnt_ != 15) ++por_cnt_;
    por_rst_ = por != 15 || !sync1;

    ++now_;
  }

  AdcAd7476 adc_;
  SdftBank sdft_;
  FrameCapture cap_;
  UartRx rx_;
  CmdDecoder cmd_;
  ByteFifo out_;
  LinkFramer fr_;
  UartTx tx_;
  std::unique_ptr<Engine> eng_;
  Bus io_;
  // The neuron unit (NEURON_UNIT): its port's clock-exact model, in the
  // engine's clocks (ucode/engine_ports.h, as the microcode tests use it).
  hls::IzhikevichUnitPort unit_;
  bool unit_present_ = false;

  // The top's own registers.
  uint8_t cfg_k_ = 0;
  bool cfg_last_ = false, cfg_valid_ = false;
  uint32_t cfg_inc_ = 0;
  bool adc_en_ = false;
  uint16_t rx_errors_ = 0;
  bool word_held_ = false;
  uint8_t word_hi_ = 0;
  // power_on_reset's, at configuration.
  bool rst_sync_[2] = {false, false};
  int por_cnt_ = 0;
  bool por_rst_ = true;

  // Time: now_ is the clock whose edge comes next (the state is during it);
  // known_ counts the clocks whose board inputs are in (inputs_ holds those
  // from now_ on).
  uint64_t now_ = 0, known_ = 0;
  // The board's pins of the clocks from now_ to known_ - 1 (at most two).
  struct Pins {
    bool reset, adc_sdata, uart_rxd;
  };
  static constexpr uint64_t kInputs = 4;
  Pins inputs_[kInputs] = {};
  std::deque<Write> writes_;
  bool running_ = false;  // the engine is out of reset
  uint64_t r0_ = 0;       // the top's clock of the engine's clock 0
};

}  // namespace

DtmfTop::DtmfTop(const hls::DtmfTopPlan& plan) {
  const std::string why = unsupported(plan);
  if (!why.empty()) throw std::invalid_argument("the cycle level does not model this build: " + why);
  if (plan.spec.engine_fast_shift) impl_ = std::make_unique<Top<true>>(plan);
  else impl_ = std::make_unique<Top<false>>(plan);
}

DtmfTop::~DtmfTop() = default;

vboard::FpgaOutputs DtmfTop::cycle(const vboard::FpgaInputs& in, uint64_t) { return impl_->cycle(in); }

void DtmfTop::open_trace(const std::string&) {
  throw std::runtime_error("the cycle level has no waveforms: --trace needs --fidelity rtl");
}

uint64_t DtmfTop::clocks() const { return impl_->clocks(); }

const std::vector<uint64_t>& DtmfTop::carrier_loads() const { return impl_->carrier_loads; }

}  // namespace eskin::cycle
