#include "ucode/dtmf_frame_bound.h"

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
  if (p.spec.neuron_lanes)
    o.wait_clocks[uint16_t(kEvIzDone)] = IzhikevichLanesPort::kLaneWriteBack + 1;
  else if (p.spec.neuron_unit)
    o.wait_clocks[uint16_t(kEvIzDone)] = kIzhikevichUnitClocks + 2;
  return o;
}

DtmfFrameBound dtmf_frame_bound(const DtmfTopPlan& p) {
  const fe_asm::Program prog = dtmf_ucode_program(dtmf_engine_image(p));
  const fe_bound::Options o = dtmf_frame_bound_options(p);
  const uint32_t main = uint32_t(prog.symbols.at("main")), frame = uint32_t(prog.symbols.at("frame"));
  DtmfFrameBound b;
  // main's wait, its test and the jump to `frame`; then the frame's work.
  const auto to_frame = fe_bound::longest_clocks(prog, main, {main, frame}, o);
  const auto body = fe_bound::longest_clocks(prog, frame, {main}, o);
  b.frame = to_frame.at(frame) + body.at(main);
  b.command = to_frame.at(main);  // the other way back to main: a command
  return b;
}

}  // namespace eskin::hls
