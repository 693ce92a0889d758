// The one C++ model of rtl/dtmf_top.v's IO bus as the frame engine sees it
// (the IO object of ucode/frame_engine.h's FrameEngine::run/step): the
// frame buffer, the registers, the command FIFO, the output FIFO's ports,
// the DFT's carrier writes and the neuron unit or lanes, decoded as the RTL
// decodes them (ucode/dtmf_io_map.h). Every C++ model of the top drives it:
// the microcode tests' clocked top (tests/ucode/dtmf_top_model.h), the
// engine load of `eskin bitstream` (host/fpga/engine_load.cpp) and the
// benchmarks' cycle model (host/bench/engine_model.cpp).
//
// The streaming build (STREAM: the engine is rtl/dtmf_chain.v's control
// plane): `frame` holds the chain's K magnitudes instead of the tokens,
// IO_HEADER releases the frame as IO_FRAME_DONE does (its bits kept in
// `headers`), IO_SITE writes are kept in `sites`, and the chain's layers
// are idle (IO_STREAM_BUSY 0; the chain's own clocks are its formulas').
//
// What the rest of the top does (the ADC, the DFT, frame capture, the link)
// stays with the caller: it fills `frame`, sets `pending`, `frame_t`,
// `adc_t` and `frame_overruns`, queues command bytes in `cmd`, and hears of
// the engine's writes through the hooks. The output FIFO is drained by a
// link that keeps up: it always has OUT_DEPTH bytes free. Counters the
// models do not drive read 0; a DFT carrier write is never pending.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "hls/carrier_magnitude.h"
#include "ucode/dtmf_io_map.h"
#include "ucode/engine_ports.h"

namespace eskin::hls {

// The streaming chain's magnitude of a window sum, as the frame buffer of a
// streaming build holds it (hls/dtmf_chain.h: CarrierMagnitude<24, 16,
// MAG_SHIFT>), at a plan's shift (N up to 4096: at most 7).
template <int SHIFT = 0>
uint32_t stream_magnitude(int shift, int32_t re, int32_t im) {
  if constexpr (SHIFT < 8) {
    if (shift != SHIFT) return stream_magnitude<SHIFT + 1>(shift, re, im);
    return CarrierMagnitude<24, 16, SHIFT>::magnitude(re, im);
  } else {
    throw std::logic_error("stream_magnitude: shift " + std::to_string(shift) + " beyond 7");
  }
}

class DtmfTopBus {
 public:
  // The plan's frame size (2 KS tokens), OUT_DEPTH, and its neuron unit or
  // lanes (NEURON_UNIT, NEURON_LANES).
  explicit DtmfTopBus(const DtmfTopPlan& p)
      : frame(size_t(2 * p.ks), 0), inc(size_t(p.ks), 0), out_depth_(p.out_depth),
        stream_(p.spec.datapath == DtmfDatapath::Streaming) {
    neuron.present = p.spec.neuron_unit && p.spec.neuron_lanes == 0;
    if (p.spec.neuron_lanes) lanes.configure(p.spec.neuron_lanes, 2 * p.T, p.C);
  }

  // ---- driven by the caller (the rest of the top) ----
  std::vector<int32_t> frame;  // the frame buffer: token k's re at 2k, im at 2k + 1
  bool pending = false;        // a frame waits for the engine
  uint32_t frame_t = 0;        // t of the frame's newest sample
  uint32_t adc_t = 0;          // the ADC's sample counter now
  uint32_t frame_overruns = 0; // frames lost because the engine was busy
  std::deque<uint8_t> cmd;     // cmd_decoder's FIFO: type, seq, len (LE), payload

  // ---- written by the engine ----
  std::vector<uint32_t> inc;   // the DFT's phase increments as last written
  bool adc_on = false;         // a carrier table reached the DFT (the ADC starts)
  size_t sdft_loads = 0;       // carrier tables loaded
  uint32_t frames_done = 0;    // frames released
  uint64_t done_clock = 0;     // the clock of the last release
  std::vector<uint8_t>* out = nullptr;  // the output FIFO's bytes, when kept
  std::vector<uint32_t> headers;  // STREAM: each frame's IO_HEADER word
  std::vector<uint32_t> sites;    // STREAM: each IO_SITE write (a taxel)
  std::vector<uint32_t> site_clears;  // STREAM: each IO_SITE_CLR write
  std::vector<size_t> sites_at_header;  // STREAM: sites.size() at each IO_HEADER

  // Hooks (each may be empty): a release of the frame buffer; bytes written
  // to the output FIFO (1 or 2, the word port's); a carrier table whose
  // last carrier was written (its count).
  std::function<void(uint64_t clock)> on_release;
  std::function<void(uint64_t clock, int bytes)> on_out;
  std::function<void(int carriers)> on_carriers;

  IzhikevichUnitPort neuron;  // NEURON_UNIT without lanes
  IzhikevichLanesPort lanes;  // NEURON_LANES
  OutFifoPort fifo;           // checks the word port's rule

  uint32_t io_read(uint16_t a, uint64_t clock) {
    if (a < kIoFrameT)  // the frame buffer (address bit 9 clear)
      return a < frame.size() ? uint32_t(frame[a]) : 0u;
    if (uint32_t d = 0; neuron.read(a, d, clock) || lanes.read(a, d, clock)) return d;
    switch (a) {
      case kIoFrameT: return frame_t;
      case kIoStatus: return (pending ? 1u : 0u) | (cmd.empty() ? 0u : 2u);
      case kIoCmd: return cmd.empty() ? 0u : cmd.front();
      case kIoOutFree: return uint32_t(out_depth_);
      case kIoAdcT: return adc_t;
      case kIoFrameOvr: return frame_overruns;
      default: return 0;
    }
  }

  void io_write(uint16_t a, uint32_t d, uint64_t clock) {
    if (neuron.write(a, d, clock) || lanes.write(a, d, clock)) return;
    if (fifo.write(a, d, clock, out)) {
      if (on_out) on_out(clock, a == kIoOutWord ? 2 : 1);
      return;
    }
    if (stream_ && a == kIoSite) return sites.push_back(d);
    if (stream_ && a == kIoSiteClr) return site_clears.push_back(d);
    if (stream_ && a == kIoHeader) headers.push_back(d), sites_at_header.push_back(sites.size());
    switch (stream_ && a == kIoHeader ? uint16_t(kIoFrameDone) : a) {
      case kIoFrameDone:
        pending = false;
        done_clock = clock;
        ++frames_done;
        if (on_release) on_release(clock);
        break;
      case kIoCmdPop:
        if (!cmd.empty()) cmd.pop_front();
        break;
      case kIoSdftK:
        cfg_k_ = int(d & 0xFF), cfg_last_ = (d >> 8) & 1;
        break;
      case kIoSdftInc:
        if (cfg_k_ >= int(inc.size()))
          throw std::logic_error("the microcode wrote DFT carrier " + std::to_string(cfg_k_) +
                                 " in clock " + std::to_string(clock) + "; the plan has " +
                                 std::to_string(inc.size()));
        inc[size_t(cfg_k_)] = d;
        if (cfg_last_) {
          adc_on = true;
          ++sdft_loads;
          if (on_carriers) on_carriers(cfg_k_ + 1);
        }
        break;
      default:
        break;
    }
  }

  uint16_t events(uint64_t clock) const {
    return uint16_t((pending ? kEvFramePending : 0) | (cmd.empty() ? 0 : kEvCmdAvail) |
                    neuron.events(clock) | lanes.events(clock));
  }

 private:
  int out_depth_ = 512;
  bool stream_ = false;
  int cfg_k_ = 0;
  bool cfg_last_ = false;
};

}  // namespace eskin::hls
