// The packet-level virtual board (`eskin simulate --fidelity packet`,
// docs/vboard.md "Fidelity levels"): a DTMF scene's packets computed by the
// FPGA's integer chain on the host (host/engine/dtmf_engine.h, bit for bit
// hls/dtmf_chain.h's packets, which the RTL's are: tests/rtl), framed as
// rtl/link_framer.v frames them (host/link/link_encoder.h) and timed per
// packet instead of per bit:
//
//   ADC      sample i is taken at clock a + i P (P: adc_ad7476's PERIOD,
//            a: the clock the engine's boot hands the carriers to the DFT,
//            from the frame engine's instruction-set model);
//   engine   a frame whose newest sample is t is pending at a + (t + 1) P,
//            and its packets go into the output FIFO W clocks later, W half
//            the microcode's static frame + command bound (the RTL writes
//            them somewhere in [pending, pending + bound]);
//   FIFO     a packet (7 header bytes + payload) is written whole only when
//            the FIFO has room (OUT_DEPTH), else dropped and counted, as
//            pkt_begin does; it leaves when its first byte goes on the wire;
//   UART     frames go out back to back, 10 bit times a byte, in order.
//
// Why the arrival error is bounded (tests/vboard/fidelity_test.cpp checks
// it against the Verilated board): the wire's departure times are a
// max-plus function of the write times (d_k = max(w_k, d_{k-1}) + n_k b),
// which moves no departure by more than the largest move of a write; a
// write moves by at most the sample's placement (P) plus half the bound
// (bound / 2), and the framer and the USB bridge add at most a byte each
// (max_error_clocks()).
//
// What this level does not model (it says so in the report): ADC timing
// violations, frame overruns (the build's clock is chosen so frames never
// overrun), and the commands other than the host's start-up set
// (SET_OUTPUT_MASK, SET_DECIMATION): any other command is refused with an
// error naming it. STATUS packets carry the model's counters; their t is
// the ADC counter at the model's write time.
#pragma once

#include <cstdint>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "host/stream/board_link.h"
#include "sim/scene.h"

namespace eskin::simulate {

struct PacketTiming {
  double clk_hz = 0;
  uint64_t period = 0;       // clocks per ADC sample (adc_ad7476's PERIOD)
  uint64_t adc_start = 0;    // clock of ADC sample 0: the engine's boot (ISS)
  uint64_t bound = 0;        // the microcode's static frame + command bound
  uint64_t byte_clocks = 0;  // 10 UART bits of round(clk / baud) clocks
  int out_depth = 0;         // the output FIFO's bytes

  uint64_t write_delay() const { return bound / 2; }
  // Clock a frame's packets enter the FIFO; t: the frame's newest sample.
  uint64_t write_clock(uint64_t t) const { return adc_start + (t + 1) * period + write_delay(); }
  // The largest |arrival here - arrival on the RTL board| the derivation
  // above allows.
  uint64_t max_error_clocks() const { return period + bound - write_delay() + 2 * byte_clocks; }
  double ns(uint64_t clocks) const { return double(clocks) * 1e9 / clk_hz; }
};

// The timing model's constants for a build (runs the engine's boot on the
// instruction-set model and the static bound).
PacketTiming packet_timing(const hls::DtmfTopPlan& plan);

// The scene's run at packet level with the host's start-up `commands`
// (framed, as the host sends them): the same BoardRun a Verilated board's
// run gives (host/stream/board_link.h), its `done` holding the figures the
// report reads and "fidelity": "packet". Throws ConfigError for a command
// this level does not model.
stream::BoardRun run_packet_board(const sim::Scene& scene, const hls::DtmfTopPlan& plan,
                                  const std::vector<std::vector<uint8_t>>& commands);

}  // namespace eskin::simulate
