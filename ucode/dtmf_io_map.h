// The frame engine's IO map in rtl/dtmf_top.v: the one definition of its
// port addresses and event bits. The microcode takes them as symbols
// (dtmf_engine_image), the C++ models of the top from here, and
// rtl/dtmf_io_map.vh is generated from them (dtmf_io_map_verilog(); the
// test DtmfIoMap.VerilogIncludeIsGenerated fails when the file is stale).
#pragma once

#include <cstdint>

namespace eskin::hls {

// IO ports of the frame engine in rtl/dtmf_top.v (reads / writes). The top
// decodes reads partially (bit 9: frame or register; bits 3:0: which
// register; with neuron lanes bit 12: a spike flag, bit 13: an event) and
// writes fully; the microcode uses only these addresses.
enum DtmfIoPort : uint16_t {
  kIoFrame = 0x000,      // r: frame token k: re at 2k, im at 2k + 1 (k = 0..KS-1)
  kIoFrameT = 0x200,     // r: t of the frame's newest sample
  kIoStatus = 0x201,     // r: bit 0 frame pending, bit 1 command available
  kIoCmd = 0x202,        // r: command FIFO head byte
  kIoOutFree = 0x203,    // r: bytes free in the output FIFO
  kIoAdcT = 0x204,       // r: the ADC sample counter now
  kIoAdcOvr = 0x205,     // r: ADC overruns (16-bit, saturating)
  kIoRxErr = 0x206,      // r: UART receive errors
  kIoCrcErr = 0x207,     // r: command frames with a bad CRC
  kIoFrmErr = 0x208,     // r: command frames with bad framing
  kIoFrameOvr = 0x209,   // r: frames lost because the engine was busy
  kIoSdftBusy = 0x20A,   // r: a DFT carrier write is pending
  kIoCmdOvf = 0x20B,     // r: command frames dropped: FIFO full
  kIoIzSpike = 0x20C,    // r: neuron unit: 1 when the last update spiked
  kIoIzV = 0x20D,        // r: neuron unit: v after the last update; w: v operand
  kIoIzU = 0x20E,        // r: neuron unit: U after the last update; w: U operand
  kIoOutByte = 0x200,    // w: one byte to the output FIFO
  kIoOutWord = 0x209,    // w: two bytes to it, bits 7:0 then 15:8 (OutFifoPort)
  kIoFrameDone = 0x201,  // w: release the frame buffer
  kIoCmdPop = 0x202,     // w: drop the command FIFO head byte
  kIoSdftK = 0x203,      // w: carrier index of the next DFT write, bit 8 = last
  kIoSdftInc = 0x204,    // w: its phase increment (starts the write)
  kIoClear = 0x205,      // w: clear the hardware counters
  kIoIzX = 0x206,        // w: neuron unit: the input x operand
  kIoIzGo = 0x207,       // w: neuron unit: the x_prev operand; starts the update
  kIoIzUGo = 0x208,      // w: neuron unit: the U operand; starts a level-input update a clock later
  kIoIzCfg = 0x220,      // w: neuron unit: constant word w of the layer block at 0x220 + w
  // Neuron lanes (NEURON_LANES: rtl/izhikevich_lanes.v, IzhikevichLanesPort below):
  kIoIzN = 0x20A,        // w: the next neuron to start or initialise; the event count restarts
  kIoIzXGo = 0x20B,      // w: that neuron's x: starts its update on the next lane
  kIoIzSV = 0x20C,       // w: v of the next initialisation
  kIoIzSU = 0x20F,       // w: U: initialises the neuron (v, U, x_prev 0, flag 0)
  kIoIzEvN = 0x20F,      // r: spike events since the last kIoIzN
  kIoIzFlag = 0x1000,    // r: at 0x1000 + C + n: neuron n's flag (bit 1), n - C's (2), n + C's (0)
  kIoIzEv = 0x2000,      // r: the neuron of event i at 0x2000 + i
};
// Engine events (the `wait` mask bits) of rtl/dtmf_top.v.
enum DtmfEvent : uint16_t {
  kEvFramePending = 1,
  kEvCmdAvail = 2,
  kEvIzDone = 4,  // the neuron unit holds the results of its last update (lanes: all written back)
};

}  // namespace eskin::hls
