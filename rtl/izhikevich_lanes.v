`default_nettype none
// izhikevich_lanes: LANES neuron units (rtl/izhikevich_layer.v) that keep
// the state of every neuron themselves, for the frame engine of
// rtl/dtmf_top.v (NEURON_LANES). The engine only hands over each neuron's
// input x; v, U and x_prev stay here, and so do the spike flags (which the
// engine's synapse_weights reads over the IO bus) and the layer's spike
// events. With the state in the engine (NEURON_UNIT alone) a neuron costs
// the engine 14 clocks of operand and result traffic; here 3 (ld, out and
// its share of the loop), which is what lets a 32x32 skin at 1 MS/s into a
// 1 ms frame at 50 MHz (docs/bitstream.md, "What limits it").
//
// The update of each neuron is IzhikevichLayer::update of
// hls/izhikevich_layer.h (the spec of its Q formats, rounding and
// saturation), computed by the unchanged izhikevich_layer; this module adds
// only storage and sequencing, so no arithmetic of its own. The C++ models
// of the top see these ports through hls::IzhikevichLanesPort
// (ucode/dtmf_engine_image.h), the clock-exact spec of the timing below.
//
// Neurons are numbered n = 0 .. 2^NB - 1 (layer l's neuron i: l T + i).
// Writes (one a clock, `data` the bus word):
//   cfg_we   constant word cfg_addr of every lane (only while idle)
//   idx_we   idx = data (the next neuron to start or to initialise), and the
//            event count restarts at 0
//   x_we     neuron idx's update with input x = data starts on the next
//            lane (round robin); idx += 1
//   sv_we    the v of the next initialisation
//   su_we    neuron idx := {v, U = data, x_prev = 0}, its flag 0; idx += 1
//            (only while idle: the microcode's boot)
// Timing (clock c: the one of x_we): c+1 the lane starts (its handshake
// edge ends c+1), with its state read in clock c (the RAM's registered
// read); its results (lane out_valid) come 13 edges later, there in clock
// c+15, when they are written back: v, U, x_prev' = input_change ? x :
// x_prev, the flag, and on a spike the event n at position count (count
// += 1). The flags, the events, the count and idle (no update started and
// not written back) show them from clock c+16 (tests/rtl/
// izhikevich_lanes_test.cpp measures all of it against the port model).
// The same lane takes its next start 14 clocks after the last (the unit's
// rate), so x_we may come every 14 / LANES clocks on average; a start to a
// busy lane is ignored, which no microcode may rely on (the port model
// throws). Write-backs come in start order, one a clock at most.
// Reads (registered, every clock, no side effect): flag_q = a column of
// three flags for synapse_weights' 3x3 code, {F(a - COLS), F(a), F(a +
// COLS)} at a = flag_addr, where F(COLS + n) is neuron n's flag and F is 0
// elsewhere (the row of zeros above layer 0; layer 1's flags lie below
// layer 0's last row, which the microcode masks off). So a = COLS + n
// gives neuron n's flag with those of the rows above and below it: one
// read instead of three, from three copies of the flags each written at
// its own offset (no adder on the read side). ev_q = the n of event
// ev_addr.
module izhikevich_lanes #(
    parameter integer LANES = 5,
    parameter integer NB = 11,     // neuron index bits: 2 T <= 2^NB
    parameter integer COLS = 32    // the skin's columns: a row of neurons
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          cfg_we,
    input  wire [4:0]    cfg_addr,
    input  wire          idx_we,
    input  wire          x_we,
    input  wire          sv_we,
    input  wire          su_we,
    input  wire [31:0]   data,
    input  wire [NB:0]   flag_addr,
    output reg  [2:0]    flag_q,
    input  wire [NB-1:0] ev_addr,
    output reg  [NB-1:0] ev_q,
    output reg  [NB:0]   ev_count,
    output wire          idle
);
  generate
    if (LANES < 2 || LANES > 8 || NB < 1 || NB > 11 || COLS < 1 || 2 * COLS > (1 << NB)) begin : g_bad_params
      izhikevich_lanes_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  // input_change (constant word 16), as the lanes read it, for x_prev'.
  reg c_ic;
  always @(posedge clk)
    if (rst) c_ic <= 1'b0;
    else if (cfg_we && cfg_addr == 5'd16) c_ic <= |data;

  // ---- state RAM {v, U, x_prev} and the start stage --------------------------
  reg [95:0]   state [0:(1 << NB) - 1];
  reg [95:0]   st_q;               // neuron idx's state, read in the x_we clock
  reg [NB-1:0] idx;
  reg [31:0]   sv;
  reg          s_valid;            // a start in this clock
  reg [31:0]   s_x;
  reg [NB-1:0] s_n;
  always @(posedge clk) begin
    st_q <= state[idx];
    s_x <= data;
    s_n <= idx;
    if (sv_we) sv <= data;
    if (rst) begin
      idx <= {NB{1'b0}};
      s_valid <= 1'b0;
    end else begin
      s_valid <= x_we;
      if (idx_we) idx <= data[NB-1:0];
      else if (x_we || su_we) idx <= idx + 1'b1;
    end
  end

  // ---- the lanes -----------------------------------------------------------
  // Each lane keeps the n and the x_prev' of the neuron it runs and offers
  // its write-back word {spike, n, v, U, x_prev'} while its results are new
  // (pend: started, not written back); at most one lane offers at a time,
  // so the write-back is the OR of the offers.
  localparam integer WBW = 1 + NB + 96;
  localparam [2:0] LAST = LANES[2:0] - 3'd1;
  reg  [2:0]           rr;       // the lane of the next start
  wire [LANES-1:0]     offer, pending;
  wire [LANES*WBW-1:0] offers;
  genvar k;
  generate
    for (k = 0; k < LANES; k = k + 1) begin : g_lane
      localparam [2:0] K = k;
      wire go = s_valid && rr == K;
      wire ready, valid, spike;
      wire [31:0] v, u;
      reg pend;
      reg [NB-1:0] n;
      reg [31:0] xp;  // x_prev' = input_change ? x : x_prev
      izhikevich_layer u_lane (
          .clk(clk), .rst(rst), .cfg_we(cfg_we), .cfg_addr(cfg_addr), .cfg_data(data),
          .in_valid(go), .in_ready(ready), .in_x(s_x), .in_x_prev(st_q[31:0]),
          .in_v(st_q[95:64]), .in_u(st_q[63:32]), .out_valid(valid), .out_spike(spike),
          .out_v(v), .out_u(u));
      always @(posedge clk) begin
        if (rst) pend <= 1'b0;
        else if (go && ready) pend <= 1'b1;
        else if (valid) pend <= 1'b0;
        if (go) begin
          n <= s_n;
          xp <= c_ic ? s_x : st_q[31:0];
        end
      end
`ifndef SYNTHESIS
      // A start to a busy lane is ignored; no microcode may rely on that
      // (hls::IzhikevichLanesPort throws on it in the C++ models).
      always @(posedge clk)
        if (!rst && go)
          assert (ready)
          else $error("izhikevich_lanes: neuron %0d started on lane %0d while that lane runs (a lane takes a start 14 clocks after its last)", s_n, k);
`endif
      assign offer[k] = pend && valid;
      assign pending[k] = pend;
      assign offers[k*WBW +: WBW] = offer[k] ? {spike, n, v, u, xp} : {WBW{1'b0}};
    end
  endgenerate
  always @(posedge clk)
    if (rst || (s_valid && rr == LAST)) rr <= 3'd0;
    else if (s_valid) rr <= rr + 3'd1;

  // ---- write-back (or, while idle, an initialisation) ----------------------
  reg [WBW-1:0] wbd;
  integer j;
  always @* begin
    wbd = {WBW{1'b0}};
    for (j = 0; j < LANES; j = j + 1) wbd = wbd | offers[j*WBW +: WBW];
  end
  wire          wb = |offer;
  wire          wb_spike = wbd[WBW-1];
  wire [NB-1:0] wb_n = su_we ? idx : wbd[96 +: NB];
  wire [95:0]   wb_state = su_we ? {sv, data, 32'd0} : wbd[95:0];
  wire          st_we = wb || su_we;
  wire          fl_d = wb && wb_spike;
  // Copy k = 0, 1, 2 holds F(a + (k - 1) COLS) at a, so neuron n's flag,
  // F(COLS + n), goes to n + 2 COLS, n + COLS and n: below 2^(NB + 1), as
  // n < 2^NB and 2 COLS <= 2^NB (checked above).
  localparam integer FB = NB + 1;
  localparam [FB-1:0] COLS_A = COLS[FB-1:0];
  wire [FB-1:0] fl_a2 = {1'b0, wb_n};
  wire [FB-1:0] fl_a1 = fl_a2 + COLS_A;
  wire [FB-1:0] fl_a0 = fl_a1 + COLS_A;
  reg          flags0 [0:(1 << FB) - 1];
  reg          flags1 [0:(1 << FB) - 1];
  reg          flags2 [0:(1 << FB) - 1];
  reg [NB-1:0] events [0:(1 << NB) - 1];
  always @(posedge clk) begin
    if (st_we) begin
      state[wb_n] <= wb_state;
      flags0[fl_a0] <= fl_d;
      flags1[fl_a1] <= fl_d;
      flags2[fl_a2] <= fl_d;
    end
    if (wb && wb_spike) events[ev_count[NB-1:0]] <= wb_n;
    flag_q <= {flags0[flag_addr], flags1[flag_addr], flags2[flag_addr]};
    ev_q <= events[ev_addr];
    if (rst || idx_we) ev_count <= {(NB + 1){1'b0}};
    else if (wb && wb_spike) ev_count <= ev_count + 1'b1;
  end

  // F's zeros: the words never written hold 0 from configuration (and in
  // simulation).
  integer z;
  initial
    for (z = 0; z < (1 << FB); z = z + 1) begin
      flags0[z] = 1'b0;
      flags1[z] = 1'b0;
      flags2[z] = 1'b0;
    end

  assign idle = !s_valid && pending == {LANES{1'b0}};
`ifndef SYNTHESIS
  // Writes allowed only while idle (above; hls::IzhikevichLanesPort's
  // busy_check in the C++ models): the constants, the next neuron's index
  // and an initialisation.
  always @(posedge clk)
    if (!rst) begin
      if (cfg_we)
        assert (idle) else $error("izhikevich_lanes: constant word %0d written while the lanes run", cfg_addr);
      if (idx_we)
        assert (idle) else $error("izhikevich_lanes: the next neuron set while the lanes run");
      if (su_we)
        assert (idle) else $error("izhikevich_lanes: neuron %0d initialised while the lanes run", idx);
    end
`endif
endmodule
`default_nettype wire
