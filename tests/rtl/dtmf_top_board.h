// Test bench for rtl/dtmf_top.v (tests/rtl/dtmf_top_test.cpp, latency
// benchmarks): the Verilated top driven by the AD7476A pin model, its UART
// line decoded bit by bit into host-link packets, commands sent bit by bit,
// and the pipeline's events read from the top's p_* probe wires.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "host/link/link_decoder.h"
#include "sim/ad7476_model.h"
#include "two_clocks.h"

namespace dtmf_bench {

using eskin::link::Packet;

// A packet as the host received it, with the cycle of its first start bit
// and the cycle its last byte's stop bit was sampled.
struct Received {
  Packet p;
  uint64_t start_cycle = 0;
  uint64_t end_cycle = 0;
};

// One (type, t, payload) triple, comparable across RTL and HLS.
struct Key {
  uint8_t type;
  uint32_t t;
  std::vector<uint8_t> payload;
  bool operator==(const Key& o) const {
    return type == o.type && t == o.t && payload == o.payload;
  }
};
inline std::string str(const Key& k) {
  std::string s = "type " + std::to_string(k.type) + " t " + std::to_string(k.t) + " [";
  for (uint8_t b : k.payload) s += std::to_string(b) + " ";
  return s + "]";
}

// Cycles of the pipeline's events for one frame (keyed by its sample t).
struct Events {
  uint64_t adc = 0;         // the sample entered sdft_bank
  uint64_t sd_last = 0;     // its last DFT token
  uint64_t frame = 0;       // frame_capture handed it to the engine
  uint64_t done = 0;        // the engine released it
  uint64_t first_out = 0;   // the engine's first output byte after `frame`
};

// Verilated top (model M) + AD7476A model + UART line codec at clk_hz with
// `cpb` clocks per UART bit; tick() is one clock. adc_clk_hz > 0: a build
// with ADC_CLK_HZ, whose adc_clk runs free at that rate beside clk (the
// ADC model driven on its edges, the UART and the probes on clk's).
template <class M>
class Board {
 public:
  Board(std::vector<uint16_t> codes12, double clk_hz, int cpb, double adc_clk_hz = 0)
      : m_(std::make_unique<M>()), adc_(std::move(codes12)), clk_hz_(clk_hz), cpb_(cpb) {
    // The ADC clock's first edge a third of its period after clk's: no
    // fixed phase between the two.
    if (adc_clk_hz > 0) two_ = std::make_unique<TwoClocks>(clk_hz, adc_clk_hz,
                                                          std::llround(0.33e15 / adc_clk_hz));
    decoder_.on_packet([this](const Packet& p) { rx_.push_back({p, frame_start_, cycle_}); });
    m_->clk = 0;
    m_->adc_clk = 0;
    m_->rst_n = 1;
    m_->uart_rxd = 1;
    m_->adc_sdata = 0;
    m_->eval();
  }

  void tick() {
    if (two_) {
      tick_two_clocks();
      return;
    }
    const double t_ns = double(cycle_ + 1) * 1e9 / clk_hz_;
    m_->adc_sdata = adc_.sdata(t_ns);
    m_->uart_rxd = rx_level();
    m_->clk = 1;
    m_->eval();
    ++cycle_;
    adc_edge(t_ns);
    // SDATA at the falling edge, half a period on (where the 40 MHz ADC
    // builds sample it: rtl/adc_ad7476.v's LAG).
    m_->adc_sdata = adc_.sdata(t_ns + 0.5e9 / clk_hz_);
    m_->clk = 0;
    m_->eval();
    uart_sample(m_->uart_txd);
    probe();
  }
  void run_until_sample(size_t n) {
    while (adc_.samples_taken() < n) tick();
  }
  void run_cycles(uint64_t n) {
    for (uint64_t i = 0; i < n; ++i) tick();
  }

  // Bytes to send to the FPGA's uart_rx (8N1, cpb clocks per bit).
  void send(const std::vector<uint8_t>& bytes) {
    for (uint8_t b : bytes) {
      tx_bits_.push_back(0);
      for (int i = 0; i < 8; ++i) tx_bits_.push_back((b >> i) & 1);
      tx_bits_.push_back(1);
    }
  }
  bool sending() const { return tx_pos_ < tx_bits_.size() * size_t(cpb_); }

  // The reset button: rst_n as the next ticks sample it.
  void set_rst_n(bool level) { m_->rst_n = level; }
  auto& root() { return *m_->rootp; }
  const eskin::sim::Ad7476Model& adc() const { return adc_; }
  uint64_t cycle() const { return cycle_; }
  const std::vector<Received>& received() const { return rx_; }
  const eskin::link::DecoderStats& link_stats() const { return decoder_.stats(); }
  int uart_framing_errors() const { return uart_errors_; }
  // Cycle of the 16th SCLK falling edge of conversion t.
  uint64_t sample_edge(uint32_t t) const { return sample_edge_.at(t); }

  std::map<uint32_t, Events> events;
  std::vector<uint64_t> carrier_loads;  // cycles of a carrier table's last write (window cleared)
  std::vector<uint32_t> carrier_load_samples;  // the first sample into the cleared window
  uint16_t out_overflows = 0;           // bytes the engine wrote into a full output FIFO
  uint32_t frames_done = 0;             // frames the engine finished

 private:
  // Edges of both clocks up to and including clk's next one.
  void tick_two_clocks() {
    for (;;) {
      const TwoClocks::Edge e = two_->next();
      if (e.b) m_->adc_sdata = adc_.sdata(e.t_ns());
      if (e.a) m_->uart_rxd = rx_level();
      m_->clk = e.a;
      m_->adc_clk = e.b;
      m_->eval();
      if (e.a) ++cycle_;
      if (e.b) {  // the pins to the model, then SDATA at adc_clk's falling edge
        adc_edge(e.t_ns());
        m_->adc_sdata = adc_.sdata(e.t_ns() + double(two_->period_b) * 0.5e-6);
      }
      m_->clk = 0;
      m_->adc_clk = 0;
      m_->eval();
      if (e.a) {
        uart_sample(m_->uart_txd);
        probe();
        return;
      }
    }
  }

  // After an edge of the ADC's clock at t_ns: the pins to the ADC model.
  void adc_edge(double t_ns) {
    adc_.drive(t_ns, m_->adc_cs_n, m_->adc_sclk);
    // 16th SCLK falling edge of a conversion: the sample's last data edge.
    if (!m_->adc_cs_n && prev_sclk_ && !m_->adc_sclk && ++falls_ == 16)
      sample_edge_.push_back(cycle_);
    if (m_->adc_cs_n) falls_ = 0;
    prev_sclk_ = m_->adc_sclk;
  }

  int rx_level() {
    if (!sending()) return 1;
    return tx_bits_[tx_pos_++ / size_t(cpb_)];
  }

  // 8N1 receiver that knows the exact bit period: a start bit first seen at
  // cycle s, bit j is sampled at s + cpb j + cpb/2 (the middle).
  void uart_sample(int level) {
    if (!busy_) {
      if (level == 0) {
        busy_ = true;
        start_ = cycle_;
        byte_ = 0;
      }
      return;
    }
    const uint64_t off = cycle_ - start_;
    if (off % uint64_t(cpb_) != uint64_t(cpb_ / 2)) return;
    const uint64_t j = off / uint64_t(cpb_);
    if (j >= 1 && j <= 8) byte_ |= uint8_t(level << (j - 1));
    if (j == 9) {
      busy_ = false;
      if (level != 1) ++uart_errors_;
      if (byte_ != 0 && !in_frame_) {
        in_frame_ = true;
        frame_start_ = start_;
      }
      if (byte_ == 0) in_frame_ = false;
      decoder_.feed(&byte_, 1);
    }
  }

  void probe() {
    auto& r = *m_->rootp;
    if (r.dtmf_top__DOT__p_cfg_done) {
      carrier_loads.push_back(cycle_);
      carrier_load_samples.push_back(seen_sample_ ? cur_t_ + 1 : 0);
    }
    if (r.dtmf_top__DOT__p_adc_fire) {
      cur_t_ = r.dtmf_top__DOT__p_adc_t;
      seen_sample_ = true;
      events[cur_t_].adc = cycle_;
    }
    if (r.dtmf_top__DOT__p_sd_fire && r.dtmf_top__DOT__p_sd_last) {
      auto it = events.find(cur_t_);
      if (it != events.end()) it->second.sd_last = cycle_;
    }
    const bool frame = r.dtmf_top__DOT__p_frame_fire;
    if (frame && !prev_frame_) {
      frame_t_ = r.dtmf_top__DOT__p_frame_t;
      events[frame_t_].frame = cycle_;
      want_out_ = true;
    }
    prev_frame_ = frame;
    if (r.dtmf_top__DOT__p_out_fire && want_out_) {
      events[frame_t_].first_out = cycle_;
      want_out_ = false;
    }
    if (r.dtmf_top__DOT__p_frame_done) {
      events[frame_t_].done = cycle_;
      ++frames_done;
    }
    out_overflows = r.dtmf_top__DOT__p_out_overflows;
    // Samples the harness keeps no events for: drop what is not a frame.
    if (events.size() > 4096) {
      for (auto it = events.begin(); it != events.end() && events.size() > 2048;)
        it = it->second.frame ? std::next(it) : events.erase(it);
    }
  }

  std::unique_ptr<M> m_;
  std::unique_ptr<TwoClocks> two_;  // adc_clk_hz > 0: clk (A) and adc_clk (B)
  eskin::sim::Ad7476Model adc_;
  double clk_hz_;
  int cpb_;
  eskin::link::LinkDecoder decoder_;
  std::vector<Received> rx_;
  uint64_t cycle_ = 0;
  bool prev_sclk_ = true;
  int falls_ = 0;
  std::vector<uint64_t> sample_edge_;
  uint32_t cur_t_ = 0, frame_t_ = 0;
  bool prev_frame_ = false, want_out_ = false, seen_sample_ = false;
  // UART receive (FPGA -> host)
  bool busy_ = false, in_frame_ = false;
  uint64_t start_ = 0, frame_start_ = 0;
  uint8_t byte_ = 0;
  int uart_errors_ = 0;
  // UART transmit (host -> FPGA)
  std::vector<int> tx_bits_;
  size_t tx_pos_ = 0;
};

}  // namespace dtmf_bench
