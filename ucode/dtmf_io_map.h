// The frame engine's IO map in rtl/dtmf_top.v: the one definition of its
// port addresses and event bits. The microcode takes them as symbols
// (dtmf_engine_image), the C++ models of the top from here, and
// rtl/dtmf_io_map.vh is generated from them (dtmf_io_map_verilog() below).
#pragma once

#include <cstdint>
#include <string>

namespace eskin::hls {

// IO ports of the frame engine in rtl/dtmf_top.v (reads / writes). The top
// decodes reads partially (bit 9: frame or register; bits 3:0: which
// register; with neuron lanes bit 12: a spike flag, bit 13: an event) and
// writes fully; the microcode uses only these addresses.
//
// X(enumerator, symbol, address, what): the symbol names the port in the
// microcode (rtl/ucode/dtmf_chain.fe) and in rtl/dtmf_io_map.vh.
#define ESKIN_DTMF_IO_PORTS(X)                                                                   \
  X(kIoFrame, IO_FRAME, 0x000,                                                                    \
    "r: frame token k: re at 2k, im at 2k + 1 (k = 0..KS-1); stream: line magnitude k at k")      \
  X(kIoFrameT, IO_FRAME_T, 0x200, "r: t of the frame's newest sample")                            \
  X(kIoStatus, IO_STATUS, 0x201, "r: bit 0 frame pending, bit 1 command available")               \
  X(kIoCmd, IO_CMD, 0x202, "r: command FIFO head byte")                                           \
  X(kIoOutFree, IO_OUT_FREE, 0x203, "r: bytes free in the output FIFO")                           \
  X(kIoAdcT, IO_ADC_T, 0x204, "r: the ADC sample counter now")                                    \
  X(kIoAdcOvr, IO_ADC_OVR, 0x205, "r: ADC overruns (16-bit, saturating)")                         \
  X(kIoRxErr, IO_RX_ERR, 0x206, "r: UART receive errors")                                         \
  X(kIoCrcErr, IO_CRC_ERR, 0x207, "r: command frames with a bad CRC")                             \
  X(kIoFrmErr, IO_FRM_ERR, 0x208, "r: command frames with bad framing")                           \
  X(kIoFrameOvr, IO_FRAME_OVR, 0x209, "r: frames lost because the engine was busy")               \
  X(kIoSdftBusy, IO_SDFT_BUSY, 0x20A, "r: a DFT carrier write is pending")                        \
  X(kIoCmdOvf, IO_CMD_OVF, 0x20B, "r: command frames dropped: FIFO full")                         \
  X(kIoIzSpike, IO_IZ_SPIKE, 0x20C, "r: neuron unit: 1 when the last update spiked")              \
  X(kIoIzV, IO_IZ_V, 0x20D, "r: neuron unit: v after the last update; w: v operand")              \
  X(kIoIzU, IO_IZ_U, 0x20E, "r: neuron unit: U after the last update; w: U operand")              \
  X(kIoOutByte, IO_OUT_BYTE, 0x200, "w: one byte to the output FIFO")                             \
  X(kIoOutWord, IO_OUT_WORD, 0x209, "w: two bytes to it, bits 7:0 then 15:8 (OutFifoPort)")       \
  X(kIoFrameDone, IO_FRAME_DONE, 0x201, "w: release the frame buffer")                            \
  X(kIoCmdPop, IO_CMD_POP, 0x202, "w: drop the command FIFO head byte")                           \
  X(kIoSdftK, IO_SDFT_K, 0x203, "w: carrier index of the next DFT write, bit 8 = last")           \
  X(kIoSdftInc, IO_SDFT_INC, 0x204, "w: its phase increment (starts the write)")                  \
  X(kIoClear, IO_CLEAR, 0x205, "w: clear the hardware counters")                                  \
  X(kIoIzX, IO_IZ_X, 0x206, "w: neuron unit: the input x operand")                                \
  X(kIoIzGo, IO_IZ_GO, 0x207, "w: neuron unit: the x_prev operand; starts the update")            \
  X(kIoIzUGo, IO_IZ_UGO, 0x208,                                                                   \
    "w: neuron unit: the U operand; starts a level-input update a clock later")                   \
  X(kIoIzCfg, IO_IZ_CFG, 0x220, "w: neuron unit: constant word w of the layer block at 0x220 + w") \
  /* Neuron lanes (NEURON_LANES: rtl/izhikevich_lanes.v, IzhikevichLanesPort): */               \
  X(kIoIzN, IO_IZ_N, 0x20A, "w: the next neuron to start or initialise; the event count restarts") \
  X(kIoIzXGo, IO_IZ_XGO, 0x20B, "w: that neuron's x: starts its update on the next lane")         \
  X(kIoIzSV, IO_IZ_SV, 0x20C, "w: v of the next initialisation")                                  \
  X(kIoIzSU, IO_IZ_SU, 0x20F, "w: U: initialises the neuron (v, U, x_prev 0, flag 0)")            \
  X(kIoIzEvN, IO_IZ_EVN, 0x20F, "r: spike events since the last kIoIzN")                          \
  X(kIoIzFlag, IO_IZ_FLAG, 0x1000,                                                                \
    "r: at 0x1000 + C + n: neuron n's flag (bit 1), n - C's (2), n + C's (0)")                    \
  X(kIoIzEv, IO_IZ_EV, 0x2000, "r: the neuron of event i at 0x2000 + i")                        \
  /* The streaming datapath (STREAM: rtl/dtmf_chain.v; the engine is its control plane): */    \
  X(kIoSite, IO_SITE, 0x210, "w: stream: make taxel i (row-major) an active site")               \
  X(kIoSiteClr, IO_SITE_CLR, 0x211, "w: stream: clear taxel i's site (a ghost reset)")           \
  X(kIoHeader, IO_HEADER, 0x212,                                                                \
    "w: stream: sites done; the frame's packets: bit 0 dense, 1 sparse, 2 spikes, 3 close")      \
  X(kIoRecip, IO_RECIP, 0x213, "w: stream: taxel reciprocal, bits 14:0, its shift at 20:16")     \
  X(kIoGhost, IO_GHOST, 0x214, "w: stream: bit 16 ghost filter on, 15:0 the release level")      \
  X(kIoSparseMin, IO_SPARSE_MIN, 0x215, "w: stream: TAXELS_SPARSE's least value")                \
  X(kIoNeurons, IO_NEURONS, 0x216, "w: stream: bit 0 the layers on; bit 1 initialise their state") \
  X(kIoWeight, IO_WEIGHT, 0x260, "w: stream: synapse weight i (0..8) at 0x260 + i")              \
  X(kIoIzCfg1, IO_IZ_CFG1, 0x240, "w: stream: layer 1's constant word w at 0x240 + w (layer 0: IO_IZ_CFG)") \
  X(kIoSpkDrop, IO_SPK_DROP, 0x210, "r: stream: spike events dropped in the window (saturating)") \
  X(kIoPktDrop, IO_PKT_DROP, 0x211, "r: stream: the chain's packets dropped for room (16-bit, saturating)") \
  X(kIoStreamBusy, IO_STREAM_BUSY, 0x212,                                                      \
    "r: stream: bit 0 the layers initialising or holding a frame's work")

// Engine events (the `wait` mask bits) of rtl/dtmf_top.v.
#define ESKIN_DTMF_EVENTS(X)                                       \
  X(kEvFramePending, EV_FRAME_PENDING, 1, "a frame waits")          \
  X(kEvCmdAvail, EV_CMD_AVAIL, 2, "a command byte waits")           \
  X(kEvIzDone, EV_IZ_DONE, 4,                                       \
    "the neuron unit holds the results of its last update (lanes: all written back)")

#define ESKIN_DTMF_IO_ENUMERATOR(e, sym, addr, what) e = addr,
enum DtmfIoPort : uint16_t { ESKIN_DTMF_IO_PORTS(ESKIN_DTMF_IO_ENUMERATOR) };
enum DtmfEvent : uint16_t { ESKIN_DTMF_EVENTS(ESKIN_DTMF_IO_ENUMERATOR) };
#undef ESKIN_DTMF_IO_ENUMERATOR

// One port or event of the map: its symbol, value and what it is.
struct DtmfIoEntry {
  const char* symbol;
  uint16_t value;
  const char* what;
};
#define ESKIN_DTMF_IO_ENTRY(e, sym, addr, what) {#sym, addr, what},
inline constexpr DtmfIoEntry kDtmfIoPorts[] = {ESKIN_DTMF_IO_PORTS(ESKIN_DTMF_IO_ENTRY)};
inline constexpr DtmfIoEntry kDtmfEvents[] = {ESKIN_DTMF_EVENTS(ESKIN_DTMF_IO_ENTRY)};
#undef ESKIN_DTMF_IO_ENTRY

// rtl/dtmf_io_map.vh, which rtl/dtmf_top.v includes: every port's address as
// a 16-bit localparam and every event's bit (ucode/dtmf_io_map.cpp).
// `eskin ucode io-map` writes it; the test DtmfIoMap.VerilogIncludeIsGenerated
// fails when the file in the tree differs from it.
std::string dtmf_io_map_verilog();

}  // namespace eskin::hls
