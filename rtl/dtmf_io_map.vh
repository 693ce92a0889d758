// The frame engine's IO map in rtl/dtmf_top.v, generated from
// ucode/dtmf_io_map.h by `eskin ucode io-map`: do not edit
// (DtmfIoMap.VerilogIncludeIsGenerated fails when it differs).
// A module includes it inside its body; it uses only some of them.
/* verilator lint_off UNUSEDPARAM */
localparam [15:0] IO_FRAME = 16'h0000;  // r: frame token k: re at 2k, im at 2k + 1 (k = 0..KS-1); stream: line magnitude k at k
localparam [15:0] IO_FRAME_T = 16'h0200;  // r: t of the frame's newest sample
localparam [15:0] IO_STATUS = 16'h0201;  // r: bit 0 frame pending, bit 1 command available
localparam [15:0] IO_CMD = 16'h0202;  // r: command FIFO head byte
localparam [15:0] IO_OUT_FREE = 16'h0203;  // r: bytes free in the output FIFO
localparam [15:0] IO_ADC_T = 16'h0204;  // r: the ADC sample counter now
localparam [15:0] IO_ADC_OVR = 16'h0205;  // r: ADC overruns (16-bit, saturating)
localparam [15:0] IO_RX_ERR = 16'h0206;  // r: UART receive errors
localparam [15:0] IO_CRC_ERR = 16'h0207;  // r: command frames with a bad CRC
localparam [15:0] IO_FRM_ERR = 16'h0208;  // r: command frames with bad framing
localparam [15:0] IO_FRAME_OVR = 16'h0209;  // r: frames lost because the engine was busy
localparam [15:0] IO_SDFT_BUSY = 16'h020A;  // r: a DFT carrier write is pending
localparam [15:0] IO_CMD_OVF = 16'h020B;  // r: command frames dropped: FIFO full
localparam [15:0] IO_IZ_SPIKE = 16'h020C;  // r: neuron unit: 1 when the last update spiked
localparam [15:0] IO_IZ_V = 16'h020D;  // r: neuron unit: v after the last update; w: v operand
localparam [15:0] IO_IZ_U = 16'h020E;  // r: neuron unit: U after the last update; w: U operand
localparam [15:0] IO_OUT_BYTE = 16'h0200;  // w: one byte to the output FIFO
localparam [15:0] IO_OUT_WORD = 16'h0209;  // w: two bytes to it, bits 7:0 then 15:8 (OutFifoPort)
localparam [15:0] IO_FRAME_DONE = 16'h0201;  // w: release the frame buffer
localparam [15:0] IO_CMD_POP = 16'h0202;  // w: drop the command FIFO head byte
localparam [15:0] IO_SDFT_K = 16'h0203;  // w: carrier index of the next DFT write, bit 8 = last
localparam [15:0] IO_SDFT_INC = 16'h0204;  // w: its phase increment (starts the write)
localparam [15:0] IO_CLEAR = 16'h0205;  // w: clear the hardware counters
localparam [15:0] IO_IZ_X = 16'h0206;  // w: neuron unit: the input x operand
localparam [15:0] IO_IZ_GO = 16'h0207;  // w: neuron unit: the x_prev operand; starts the update
localparam [15:0] IO_IZ_UGO = 16'h0208;  // w: neuron unit: the U operand; starts a level-input update a clock later
localparam [15:0] IO_IZ_CFG = 16'h0220;  // w: neuron unit: constant word w of the layer block at 0x220 + w
localparam [15:0] IO_IZ_N = 16'h020A;  // w: the next neuron to start or initialise; the event count restarts
localparam [15:0] IO_IZ_XGO = 16'h020B;  // w: that neuron's x: starts its update on the next lane
localparam [15:0] IO_IZ_SV = 16'h020C;  // w: v of the next initialisation
localparam [15:0] IO_IZ_SU = 16'h020F;  // w: U: initialises the neuron (v, U, x_prev 0, flag 0)
localparam [15:0] IO_IZ_EVN = 16'h020F;  // r: spike events since the last kIoIzN
localparam [15:0] IO_IZ_FLAG = 16'h1000;  // r: at 0x1000 + C + n: neuron n's flag (bit 1), n - C's (2), n + C's (0)
localparam [15:0] IO_IZ_EV = 16'h2000;  // r: the neuron of event i at 0x2000 + i
localparam [15:0] IO_SITE = 16'h0210;  // w: stream: make taxel i (row-major) an active site
localparam [15:0] IO_SITE_CLR = 16'h0211;  // w: stream: clear taxel i's site (a ghost reset)
localparam [15:0] IO_HEADER = 16'h0212;  // w: stream: sites done; the frame's packets: bit 0 dense, 1 sparse, 2 spikes, 3 close
localparam [15:0] IO_RECIP = 16'h0213;  // w: stream: taxel reciprocal, bits 14:0, its shift at 20:16
localparam [15:0] IO_GHOST = 16'h0214;  // w: stream: bit 16 ghost filter on, 15:0 the release level
localparam [15:0] IO_SPARSE_MIN = 16'h0215;  // w: stream: TAXELS_SPARSE's least value
localparam [15:0] IO_NEURONS = 16'h0216;  // w: stream: bit 0 the layers on; bit 1 initialise their state
localparam [15:0] IO_WEIGHT = 16'h0260;  // w: stream: synapse weight i (0..8) at 0x260 + i
localparam [15:0] IO_IZ_CFG1 = 16'h0240;  // w: stream: layer 1's constant word w at 0x240 + w (layer 0: IO_IZ_CFG)
localparam [15:0] IO_SPK_DROP = 16'h0210;  // r: stream: spike events dropped in the window (saturating)
localparam [15:0] IO_PKT_DROP = 16'h0211;  // r: stream: the chain's packets dropped for room (16-bit, saturating)
localparam [15:0] IO_STREAM_BUSY = 16'h0212;  // r: stream: bit 0 the layers initialising or holding a frame's work
localparam integer EV_FRAME_PENDING_BIT = 0;  // a frame waits
localparam integer EV_CMD_AVAIL_BIT = 1;  // a command byte waits
localparam integer EV_IZ_DONE_BIT = 2;  // the neuron unit holds the results of its last update (lanes: all written back)
/* verilator lint_on UNUSEDPARAM */
