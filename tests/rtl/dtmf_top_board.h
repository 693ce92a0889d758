// Test bench for rtl/dtmf_top.v (used by tests/rtl/dtmf_top_test.cpp): the
// Verilated top driven by the AD7476A pin model, its UART line decoded bit
// by bit into host-link packets, commands sent bit by bit, and the
// pipeline handshakes read from the top's p_* probe wires.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "host/link/link_decoder.h"
#include "sim/ad7476_model.h"

namespace dtmf_bench {

using eskin::link::Packet;
constexpr double kClkHz = 12e6;
constexpr int kCpb = 4;          // uart_tx clocks per bit: 12 MHz / 3 Mbaud
constexpr int kPeriod = 343;     // adc_ad7476 clocks per sample: round(12e6 / 35e3)

// A packet as the host received it, with the cycle of its first start bit.
struct Received {
  Packet p;
  uint64_t start_cycle = 0;
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

// Verilated top (model M) + AD7476A model + UART line codec; tick() is one
// clock. The probes are dtmf_top's p_* wires (verilator public_flat_rd).
template <class M>
class Board {
 public:
  explicit Board(std::vector<uint16_t> codes12)
      : m_(std::make_unique<M>()), adc_(std::move(codes12)) {
    decoder_.on_packet([this](const Packet& p) { rx_.push_back({p, frame_start_}); });
    m_->clk = 0;
    m_->rst_n = 1;
    m_->uart_rxd = 1;
    m_->adc_sdata = 0;
    m_->eval();
  }

  void tick() {
    const double t_ns = double(cycle_ + 1) * 1e9 / kClkHz;
    m_->adc_sdata = adc_.sdata(t_ns);
    m_->uart_rxd = rx_level();
    m_->clk = 1;
    m_->eval();
    m_->clk = 0;
    m_->eval();
    ++cycle_;
    adc_.drive(t_ns, m_->adc_cs_n, m_->adc_sclk);
    // 16th SCLK falling edge of a conversion: the sample's last data edge.
    if (!m_->adc_cs_n && prev_sclk_ && !m_->adc_sclk && ++falls_ == 16)
      sample_edge_.push_back(cycle_);
    if (m_->adc_cs_n) falls_ = 0;
    prev_sclk_ = m_->adc_sclk;
    uart_sample(m_->uart_txd);
    probe();
  }
  void run_until_sample(size_t n) {
    while (adc_.samples_taken() < n) tick();
  }

  // Bytes to send to the FPGA's uart_rx (8N1, kCpb clocks per bit).
  void send(const std::vector<uint8_t>& bytes) {
    for (uint8_t b : bytes) {
      tx_bits_.push_back(0);
      for (int i = 0; i < 8; ++i) tx_bits_.push_back((b >> i) & 1);
      tx_bits_.push_back(1);
    }
  }

  auto& root() { return *m_->rootp; }
  const eskin::sim::Ad7476Model& adc() const { return adc_; }
  uint64_t cycle() const { return cycle_; }
  const std::vector<Received>& received() const { return rx_; }
  const eskin::link::DecoderStats& link_stats() const { return decoder_.stats(); }
  int uart_framing_errors() const { return uart_errors_; }
  // Cycle of the 16th SCLK falling edge of conversion t.
  uint64_t sample_edge(uint32_t t) const { return sample_edge_.at(t); }

  // Cycles (as counted by tick()) in which a pipeline handshake happened,
  // keyed by the sample counter t of the frame.
  struct Events {
    uint64_t adc = 0, sd_first = 0, sd_last = 0, mg_first = 0, mg_last = 0, tx_first = 0,
             tx_last = 0, nr_first = 0, nr_last = 0;
    std::map<uint8_t, uint64_t> hdr;  // packet type -> link_framer header handshake
  };
  std::map<uint32_t, Events> events;
  bool tag_error = false;
  uint64_t mask_change_cycle = 0;  // last change of cmd_decoder.out_mask
  std::vector<uint64_t> carrier_loads;  // cycles of the last carrier write to sdft_bank

 private:
  int rx_level() {
    if (tx_pos_ >= tx_bits_.size() * kCpb) return 1;
    return tx_bits_[tx_pos_++ / kCpb];
  }

  // 8N1 receiver that knows the exact bit period: a start bit first seen at
  // cycle s, bit j is sampled at s + kCpb j + kCpb/2 (the middle).
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
    if (off % kCpb != kCpb / 2) return;
    const uint64_t j = off / kCpb;
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
    if (r.dtmf_top__DOT__tag_error) tag_error = true;
    if (r.dtmf_top__DOT__p_mask != last_mask_) {
      last_mask_ = r.dtmf_top__DOT__p_mask;
      mask_change_cycle = cycle_;
    }
    if (r.dtmf_top__DOT__p_cfg_done) carrier_loads.push_back(cycle_);
    if (r.dtmf_top__DOT__p_adc_fire) events[r.dtmf_top__DOT__p_adc_t].adc = cycle_;
    const auto mark = [this](bool last, uint64_t& first, uint64_t& lst) {
      if (first == 0) first = cycle_;
      if (last) lst = cycle_;
    };
    if (r.dtmf_top__DOT__p_sd_fire) {
      Events& e = events[r.dtmf_top__DOT__p_sd_t];
      mark(r.dtmf_top__DOT__p_sd_last, e.sd_first, e.sd_last);
    }
    if (r.dtmf_top__DOT__p_mg_fire) {
      Events& e = events[r.dtmf_top__DOT__p_mg_t];
      mark(r.dtmf_top__DOT__p_mg_last, e.mg_first, e.mg_last);
    }
    if (r.dtmf_top__DOT__p_tx_fire) {
      Events& e = events[r.dtmf_top__DOT__p_tx_t];
      mark(r.dtmf_top__DOT__p_tx_last, e.tx_first, e.tx_last);
    }
    if (r.dtmf_top__DOT__p_nr_fire) {
      Events& e = events[r.dtmf_top__DOT__p_nr_t];
      mark(r.dtmf_top__DOT__p_nr_last, e.nr_first, e.nr_last);
    }
    if (r.dtmf_top__DOT__p_hdr_fire)
      events[r.dtmf_top__DOT__p_hdr_t].hdr[r.dtmf_top__DOT__p_hdr_type] = cycle_;
  }

  std::unique_ptr<M> m_;
  eskin::sim::Ad7476Model adc_;
  eskin::link::LinkDecoder decoder_;
  std::vector<Received> rx_;
  uint64_t cycle_ = 0;
  bool prev_sclk_ = true;
  int falls_ = 0;
  std::vector<uint64_t> sample_edge_;
  int last_mask_ = -1;
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
