#include "ucode/dtmf_frame_bound.h"

#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "ucode/dtmf_engine_image.h"
#include "ucode/dtmf_io_map.h"
#include "ucode/dtmf_ucode.h"
#include "ucode/engine_ports.h"

namespace eskin::hls {

fe_bound::Options dtmf_frame_bound_options(const DtmfTopPlan& p) {
  fe_bound::Options o;
  o.fast_shift = p.spec.engine_fast_shift;
  o.file = "rtl/ucode/dtmf_chain.fe";
  o.wait_clocks[uint16_t(kEvFramePending | kEvCmdAvail)] = 1;
  // The latest start is the one EV_IZ_DONE reports: the unit's (a start
  // while busy is a contract violation) or the lanes' last x write (each
  // starts at once on its lane, so the last written back is the last).
  if (p.spec.neuron_lanes) {
    o.wait_clocks[uint16_t(kEvIzDone)] = IzhikevichLanesPort::kLaneWriteBack + 1;
    o.wait_starts[uint16_t(kEvIzDone)] = {uint16_t(kIoIzXGo)};
  } else if (p.spec.neuron_unit) {
    o.wait_clocks[uint16_t(kEvIzDone)] = kIzhikevichUnitClocks + 2;
    o.wait_starts[uint16_t(kEvIzDone)] = {uint16_t(kIoIzGo), uint16_t(kIoIzUGo)};
  }
  return o;
}

namespace {
// A frame's and a command's bound of the program assembled with `image`.
std::pair<uint64_t, uint64_t> frame_and_command(const EngineImage& image,
                                                const fe_bound::Options& o) {
  const fe_asm::Program prog = dtmf_ucode_program(image);
  const uint32_t main = uint32_t(prog.symbols.at("main")), frame = uint32_t(prog.symbols.at("frame"));
  // main's wait, its test and the jump to `frame`; then the frame's work.
  const auto to_frame = fe_bound::longest_clocks(prog, main, {main, frame}, o);
  const auto body = fe_bound::longest_clocks(prog, frame, {main}, o);
  // The other way back to main: a command.
  return {to_frame.at(frame) + body.at(main), to_frame.at(main)};
}
}  // namespace

DtmfFrameBound dtmf_frame_bound(const DtmfTopPlan& p) {
  const fe_bound::Options o = dtmf_frame_bound_options(p);
  EngineImage image = dtmf_engine_image(p);
  DtmfFrameBound b;
  std::tie(b.frame, b.command) = frame_and_command(image, o);
  // Without the plan's assumptions: SET_NEURON's largest shift counts (the
  // gain shift's left part is -gain_shift, its right part gain_shift; u_frac
  // is kept as u_frac - 22) and the longest frame the command FIFO holds.
  auto hi = [](const char* name) {
    for (int q = 0; q < 16; ++q)
      if (std::string(neuron_params()[q].name) == name) return neuron_params()[q];
    throw std::logic_error(std::string("neuron_params: no ") + name);
  };
  for (auto& [name, value] : image.symbols) {
    if (name == "NSH4") value = hi("u_frac").hi - 22;
    if (name == "NSH7") value = hi("s2").hi;
    if (name == "NSH9") value = hi("s3").hi;
    if (name == "NSH11") value = hi("s4").hi;
    if (name == "NSH13") value = hi("gain_shift").hi;
    if (name == "NSH14") value = -hi("gain_shift").lo;
    if (name == "NSH15") value = hi("x_shift").hi;
    if (name == "CMD_PAYLOAD") value = kDtmfCmdFifoBytes - 4;
    if (name == "SPKWIN") value = p.max_spikes;  // any decimation
    if (name == "SPARSE") value = 1;             // any mask
  }
  std::tie(b.frame_any, b.command_any) = frame_and_command(image, o);
  if (p.spec.datapath == DtmfDatapath::Streaming) {
    b.chain = uint64_t(dtmf_chain_frame_clocks(p, p.mask));
    b.chain_any = uint64_t(dtmf_chain_frame_clocks(p, 0xFF));
    b.frame += b.chain;
    b.frame_any += b.chain_any;
  }
  return b;
}

}  // namespace eskin::hls
