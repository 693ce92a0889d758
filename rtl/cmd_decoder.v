// cmd_decoder: configuration commands from the host (bytes from uart_rx) ->
// configuration registers. Frame format and register map: docs/protocol.md.
//
// Frames are COBS-decoded on the fly (no buffer: the implied zero of a block
// is only emitted when the next block starts, so a frame's trailing block
// adds none). Each raw byte updates a CRC-16/CCITT-FALSE register (rtl/
// crc16.v); the frame's big-endian CRC makes it 0 at the end. At the 0x00
// delimiter the frame is judged, in this order:
//   1. structure: COBS block cut short, fewer than 10 raw bytes, raw length
//      != 10 + len field, or a UART error (rx_error) during the frame
//      -> dropped, frame_errors + 1;
//   2. CRC register != 0 -> dropped, crc_errors + 1;
//   3. contents: unknown type, payload length wrong for the type, index or
//      value out of range -> rejected: rejected + 1, last_reject_{type,
//      reason, seq} updated, status_req pulses (so a status packet reports
//      it); registers unchanged;
//   4. otherwise applied: accepted + 1, cfg_changed pulses.
// Counters saturate at 16'hFFFF. Bytes are taken every cycle (s_ready = 1);
// one command is applied one clock after its delimiter is taken.
//
// Commands (payload little endian):
//   0x81 SET_CARRIER_INC  k u8, inc u32      k < K, 1 <= inc < 2^(PHASE_W-1)
//   0x82 SET_THRESHOLD    id u8, value u16   id < NTHR
//   0x83 SET_NEURON       id u8, value s32   id < NNP, NEURON_LO[id] <= value <= NEURON_HI[id]
//   0x84 SET_OUTPUT_MASK  mask u8            bits 7..4 zero
//   0x85 SET_DECIMATION   stream u8, d u16   stream < 3, 1 <= d <= DECIM_MAX
//   0x86 REQUEST_STATUS   (empty)            status_req pulse
//   0x87 CLEAR_COUNTERS   (empty)            counters and last_reject_* to 0
// Reject reasons: 1 unknown type, 2 bad payload length, 3 bad index,
// 4 bad value, 5 reserved bits set.
module cmd_decoder #(
    parameter integer K       = 6,   // carriers (rows + cols)
    parameter integer PHASE_W = 32,  // phase increment width of sdft_bank
    parameter integer NTHR    = 4,   // thresholds
    parameter integer NNP     = 4,   // neuron parameters
    // Neuron parameter ids (izhikevich_layer): 0 V_RESET (c, Q9.22 mV,
    // -128 <= c < 30 mV), 1 U_JUMP (k d, Q.U_FRAC, 0 .. 2^30-1), 2 GAIN
    // (int16), 3 X_SHIFT (0..31). Packed, id 0 in the low 32 bits.
    parameter [NNP*32-1:0] NEURON_LO   = {32'd0, 32'hFFFF8000, 32'd0, 32'hE0000000},
    parameter [NNP*32-1:0] NEURON_HI   = {32'd31, 32'h00007FFF, 32'h3FFFFFFF, 32'h077FFFFF},
    parameter [NNP*32-1:0] NEURON_INIT = {32'd1, 32'd20433, 32'd185987, 32'hF2400000},
    parameter [K*PHASE_W-1:0] INC_INIT = {K*PHASE_W{1'b0}},
    parameter [NTHR*16-1:0] THR_INIT   = {NTHR*16{1'b0}},
    parameter [7:0]  MASK_INIT  = 8'h0F,
    parameter [47:0] DECIM_INIT = {16'd1000, 16'd35, 16'd35},  // status, taxels, amplitudes
    parameter [15:0] DECIM_MAX  = 16'hFFFF
) (
    input  wire                   clk,
    input  wire                   rst,
    input  wire                   s_valid,
    output wire                   s_ready,
    input  wire [7:0]             s_data,
    input  wire                   rx_error,    // uart_rx frame_err | overrun
    // Configuration registers.
    output reg  [K*PHASE_W-1:0]   carrier_inc, // carrier k at [k*PHASE_W +: PHASE_W]
    output reg  [NTHR*16-1:0]     thresholds,  // id at [id*16 +: 16]
    output reg  [NNP*32-1:0]      neuron,      // id at [id*32 +: 32]
    output reg  [3:0]             out_mask,    // 0 amplitudes, 1 taxels, 2 spikes, 3 status
    output reg  [47:0]            decim,       // stream s at [s*16 +: 16]
    output reg                    cfg_changed, // pulse: a command was applied
    output reg                    status_req,  // pulse: REQUEST_STATUS or a rejection
    // Status counters.
    output reg  [15:0]            crc_errors,
    output reg  [15:0]            frame_errors,
    output reg  [15:0]            accepted,
    output reg  [15:0]            rejected,
    output reg  [7:0]             last_reject_type,
    output reg  [7:0]             last_reject_reason,
    output reg  [7:0]             last_reject_seq
);
  assign s_ready = 1'b1;

  // ---------------- COBS decoding and frame accumulation ----------------
  reg [7:0]  code_rem;   // data bytes left in the current block
  reg        pend_zero;  // the current block's implied zero, if another block follows
  reg        in_frame;
  reg        bad;        // UART error inside this frame
  reg [16:0] count;      // raw bytes (saturating)
  reg [15:0] crc;
  reg [7:0]  typ, seqn;
  reg [15:0] len;
  reg [7:0]  pb0, pb1, pb2, pb3, pb4;  // first five payload bytes

  wire take = s_valid;
  wire delim = take && s_data == 8'd0;
  wire is_code = take && !delim && code_rem == 8'd0;
  // Raw byte this cycle: a data byte, or the pending zero before a new block.
  wire raw_en = take && !delim && (!is_code || pend_zero);
  wire [7:0] raw = is_code ? 8'd0 : s_data;
  wire [15:0] crc_next;
  crc16 u_crc (.crc_in(crc), .data(raw), .crc_out(crc_next));

  // Judgement at the delimiter (uses the registers before this cycle).
  wire struct_ok = !bad && code_rem == 8'd0 && count >= 17'd10 &&
                   count == {1'b0, len} + 17'd10;
  wire crc_ok = (crc == 16'd0);
  wire do_frame = delim && in_frame;

  // ---------------- command checks ----------------
  localparam [7:0] R_OK = 8'd0, R_TYPE = 8'd1, R_LEN = 8'd2, R_INDEX = 8'd3,
                   R_VALUE = 8'd4, R_RESERVED = 8'd5;
  wire [31:0] v32 = {pb4, pb3, pb2, pb1};
  wire [15:0] v16 = {pb2, pb1};
  wire [PHASE_W-1:0] inc = v32[PHASE_W-1:0];
  wire inc_ok = inc != {PHASE_W{1'b0}} && !inc[PHASE_W-1] &&
                (PHASE_W == 32 || v32 >> PHASE_W == 32'd0);
  reg [31:0] nlo, nhi;
  integer j;
  always @(*) begin
    nlo = 32'd0;
    nhi = 32'd0;
    for (j = 0; j < NNP; j = j + 1)
      if (pb0 == j[7:0]) begin
        nlo = NEURON_LO[j*32 +: 32];
        nhi = NEURON_HI[j*32 +: 32];
      end
  end
  wire neuron_ok = $signed(v32) >= $signed(nlo) && $signed(v32) <= $signed(nhi);

  reg [7:0] reason;
  always @(*) begin
    reason = R_OK;
    case (typ)
      8'h81:   reason = (len != 16'd5) ? R_LEN : ({24'd0, pb0} >= K) ? R_INDEX :
                        !inc_ok ? R_VALUE : R_OK;
      8'h82:   reason = (len != 16'd3) ? R_LEN : ({24'd0, pb0} >= NTHR) ? R_INDEX : R_OK;
      8'h83:   reason = (len != 16'd5) ? R_LEN : ({24'd0, pb0} >= NNP) ? R_INDEX :
                        !neuron_ok ? R_VALUE : R_OK;
      8'h84:   reason = (len != 16'd1) ? R_LEN : (pb0[7:4] != 4'd0) ? R_RESERVED : R_OK;
      // With the default DECIM_MAX = 16'hFFFF the upper bound is always met.
      /* verilator lint_off CMPCONST */
      8'h85:   reason = (len != 16'd3) ? R_LEN : (pb0 >= 8'd3) ? R_INDEX :
                        (v16 == 16'd0 || v16 > DECIM_MAX) ? R_VALUE : R_OK;
      /* verilator lint_on CMPCONST */
      8'h86, 8'h87: reason = (len != 16'd0) ? R_LEN : R_OK;
      default: reason = R_TYPE;
    endcase
  end

  integer f;

  function automatic [15:0] sat_inc(input [15:0] x);
    sat_inc = (x == 16'hFFFF) ? x : x + 16'd1;
  endfunction

  // Error and command counters: cleared at reset and by CLEAR_COUNTERS.
  task automatic clear_counters;
    begin
      crc_errors         <= 16'd0;
      frame_errors       <= 16'd0;
      accepted           <= 16'd0;
      rejected           <= 16'd0;
      last_reject_type   <= 8'd0;
      last_reject_reason <= 8'd0;
      last_reject_seq    <= 8'd0;
    end
  endtask

  always @(posedge clk) begin
    cfg_changed <= 1'b0;
    status_req  <= 1'b0;
    if (rst) begin
      code_rem    <= 8'd0;
      pend_zero   <= 1'b0;
      in_frame    <= 1'b0;
      bad         <= 1'b0;
      count       <= 17'd0;
      crc         <= 16'hFFFF;
      typ         <= 8'd0;
      seqn        <= 8'd0;
      len         <= 16'd0;
      {pb0, pb1, pb2, pb3, pb4} <= 40'd0;
      carrier_inc <= INC_INIT;
      thresholds  <= THR_INIT;
      neuron      <= NEURON_INIT;
      out_mask    <= MASK_INIT[3:0];
      decim       <= DECIM_INIT;
      clear_counters();
    end else begin
      // A byte lost by the UART belongs to the frame being received (or
      // about to start): that frame cannot be trusted.
      if (rx_error) bad <= 1'b1;

      if (delim) begin
        code_rem  <= 8'd0;
        pend_zero <= 1'b0;
        in_frame  <= 1'b0;
        bad       <= 1'b0;
        count     <= 17'd0;
        crc       <= 16'hFFFF;
      end else if (take) begin
        in_frame <= 1'b1;
        if (is_code) begin
          code_rem  <= s_data - 8'd1;
          pend_zero <= (s_data != 8'hFF);
        end else begin
          code_rem <= code_rem - 8'd1;
        end
        if (raw_en) begin
          crc <= crc_next;
          if (count != 17'h1FFFF) count <= count + 17'd1;
          case (count)
            17'd0:  typ <= raw;
            17'd1:  seqn <= raw;
            17'd6:  len[7:0] <= raw;
            17'd7:  len[15:8] <= raw;
            17'd8:  pb0 <= raw;
            17'd9:  pb1 <= raw;
            17'd10: pb2 <= raw;
            17'd11: pb3 <= raw;
            17'd12: pb4 <= raw;
            default: ;
          endcase
        end
      end

      if (do_frame) begin
        if (!struct_ok) begin
          frame_errors <= sat_inc(frame_errors);
        end else if (!crc_ok) begin
          crc_errors <= sat_inc(crc_errors);
        end else if (reason != R_OK) begin
          rejected           <= sat_inc(rejected);
          last_reject_type   <= typ;
          last_reject_reason <= reason;
          last_reject_seq    <= seqn;
          status_req         <= 1'b1;
        end else begin
          accepted    <= sat_inc(accepted);
          cfg_changed <= 1'b1;
          // Constant part-selects with one enable per field (a variable
          // part-select would build a shifter over the whole vector).
          for (f = 0; f < K; f = f + 1)
            if (typ == 8'h81 && pb0 == f[7:0]) carrier_inc[f*PHASE_W +: PHASE_W] <= inc;
          for (f = 0; f < NTHR; f = f + 1)
            if (typ == 8'h82 && pb0 == f[7:0]) thresholds[f*16 +: 16] <= v16;
          for (f = 0; f < NNP; f = f + 1)
            if (typ == 8'h83 && pb0 == f[7:0]) neuron[f*32 +: 32] <= v32;
          for (f = 0; f < 3; f = f + 1)
            if (typ == 8'h85 && pb0 == f[7:0]) decim[f*16 +: 16] <= v16;
          case (typ)
            8'h81, 8'h82, 8'h83, 8'h85: ;
            8'h84: out_mask <= pb0[3:0];
            8'h86: status_req <= 1'b1;
            default: clear_counters();  // 8'h87 CLEAR_COUNTERS
          endcase
        end
      end
    end
  end
endmodule
