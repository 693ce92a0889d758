`default_nettype none
// hall_cmd: the Hall top's command interpreter. It reads whole, well-formed
// command frames from cmd_decoder's FIFO (type, seq, len u16 LE, payload;
// framing and CRC were checked there), judges their contents and applies
// them to the decoding blocks the build has (docs/protocol.md section 9):
//   0x98 HALL_LOAD_C        row u8, col u8, value s32  -> ft_calibrate's C RAM
//   0x99 HALL_SET_BASELINE  sensor u8, axis u8, value s16 -> hall_baseline
//   0x9A HALL_RECAPTURE     (none)                      -> hall_baseline
//   0x9B HALL_LOAD_CURVE    cell u8, index u8, which u8, value s32
//                                                       -> force_curve's curve RAMs
//   0x9C HALL_SET_DECOUPLE  k1 s16, c1 s32, k2 s16, c2 s32 -> held here for
//                           hall_decouple (reset: k 1.0, c 0, the HLS defaults)
// A type whose block the build lacks (HAS_FT / HAS_BASELINE / HAS_CURVE /
// HAS_DECOUPLE 0), or any other
// type, is rejected as unknown: no command is accepted and ignored.
// Checks, in order: type (reason 1), payload length (2), index range (3).
// A rejected command changes nothing; it counts in `rejected`, records its
// type, reason and seq in last_*, and pulses `reject` (the top answers with
// a HALL_DECODE_STATUS packet). Accepted commands count in `accepted` and
// take effect in the cycle after their last byte (one-cycle pulses on the
// block's load port). Counters are 16-bit and saturate.
// Reading cmd_decoder: `pop` is combinational (avail while a byte is
// wanted); the byte in `head` is taken in that cycle.
module hall_cmd #(
    parameter integer NS = 16,           // hall_baseline sensors (set_sensor < NS)
    parameter integer HAS_BASELINE = 1,
    parameter integer HAS_FT = 0,
    parameter integer HAS_CURVE = 0,
    parameter integer HAS_DECOUPLE = 0,
    parameter integer NC = 1,            // force_curve cells (cell < NC)
    parameter integer NBP = 13,          // force_curve breakpoints (index < NBP)
    parameter integer SW = (NS > 1) ? $clog2(NS) : 1,
    parameter integer CW = (NC > 1) ? $clog2(NC) : 1
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          avail,
    input  wire [7:0]    head,
    output wire          pop,
    // ft_calibrate C RAM
    output reg           c_valid,
    output reg  [2:0]    c_row,
    output reg  [3:0]    c_col,
    output reg  [31:0]   c_value,
    // hall_baseline
    output reg           set_valid,
    output reg  [SW-1:0] set_sensor,
    output reg  [1:0]    set_axis,
    output reg  [15:0]   set_value,
    output reg           recapture,
    // force_curve curve RAMs
    output reg           t_valid,
    output reg  [CW-1:0] t_cell,
    output reg  [4:0]    t_index,
    output reg  [1:0]    t_which,
    output reg  [31:0]   t_value,
    // hall_decouple compensation (held)
    output reg  [15:0]   dc_k1,
    output reg  [31:0]   dc_c1,
    output reg  [15:0]   dc_k2,
    output reg  [31:0]   dc_c2,
    // report
    output reg  [15:0]   accepted,
    output reg  [15:0]   rejected,
    output reg  [7:0]    last_type,
    output reg  [7:0]    last_reason,
    output reg  [7:0]    last_seq,
    output reg           reject
);
  generate
    if (NS < 1 || NS > 255 || SW < 1 || (NS > (1 << SW))) begin : g_bad_ns
      hall_cmd_NS_must_be_1_to_255_and_fit_SW u_bad ();
    end
    if (HAS_FT != 0 && HAS_BASELINE == 0) begin : g_bad_ft
      hall_cmd_HAS_FT_needs_HAS_BASELINE u_bad ();
    end
    if ((HAS_CURVE != 0 || HAS_DECOUPLE != 0) && HAS_BASELINE == 0) begin : g_bad_dec
      hall_cmd_HAS_CURVE_and_HAS_DECOUPLE_need_HAS_BASELINE u_bad ();
    end
    if (NC < 1 || NC > 64 || NC > (1 << CW) || NBP < 3 || NBP > 32) begin : g_bad_nc
      hall_cmd_NC_must_be_1_to_64_and_fit_CW_and_NBP_3_to_32 u_bad ();
    end
  endgenerate

  localparam [7:0] T_LOAD_C = 8'h98, T_SET_BASELINE = 8'h99, T_RECAPTURE = 8'h9A,
                   T_LOAD_CURVE = 8'h9B, T_SET_DECOUPLE = 8'h9C;
  localparam [1:0] S_HDR = 2'd0, S_PAY = 2'd1, S_EXEC = 2'd2;
  reg [1:0]  state;
  reg [1:0]  hidx;        // header byte: 0 type, 1 seq, 2 len lo, 3 len hi
  reg [7:0]  typ, seq;
  reg [15:0] len, got;    // payload length, payload bytes taken
  reg [7:0]  pay [0:11];  // the first 12 payload bytes (the longest command)

  assign pop = avail && (state != S_EXEC);

  // The judgement of the frame in pay[] (valid in S_EXEC).
  wire is_c = HAS_FT != 0 && typ == T_LOAD_C;
  wire is_b = HAS_BASELINE != 0 && typ == T_SET_BASELINE;
  wire is_r = HAS_BASELINE != 0 && typ == T_RECAPTURE;
  wire is_l = HAS_CURVE != 0 && typ == T_LOAD_CURVE;
  wire is_d = HAS_DECOUPLE != 0 && typ == T_SET_DECOUPLE;
  wire [15:0] want_len = is_c ? 16'd6 : is_b ? 16'd4 : is_l ? 16'd7 : is_d ? 16'd12 : 16'd0;
  wire idx_ok = is_c ? (pay[0] < 8'd6 && pay[1] < 8'd9) :
                is_b ? ({1'b0, pay[0]} < NS[8:0] && pay[1] < 8'd3) :
                is_l ? ({1'b0, pay[0]} < NC[8:0] && {1'b0, pay[1]} < NBP[8:0] && pay[2] < 8'd3) :
                1'b1;
  wire [7:0] reason = !(is_c || is_b || is_r || is_l || is_d) ? 8'd1 : (len != want_len) ? 8'd2 :
                      !idx_ok ? 8'd3 : 8'd0;

  function automatic [15:0] sat_inc(input [15:0] x);
    sat_inc = (x == 16'hFFFF) ? x : x + 16'd1;
  endfunction

  integer k;
  always @(posedge clk) begin
    if (rst) begin
      state <= S_HDR;
      hidx <= 2'd0;
      typ <= 8'd0;
      seq <= 8'd0;
      len <= 16'd0;
      got <= 16'd0;
      for (k = 0; k < 12; k = k + 1) pay[k] <= 8'd0;
      t_valid <= 1'b0;
      t_cell <= {CW{1'b0}};
      t_index <= 5'd0;
      t_which <= 2'd0;
      t_value <= 32'd0;
      dc_k1 <= 16'h4000;
      dc_c1 <= 32'd0;
      dc_k2 <= 16'h4000;
      dc_c2 <= 32'd0;
      c_valid <= 1'b0;
      c_row <= 3'd0;
      c_col <= 4'd0;
      c_value <= 32'd0;
      set_valid <= 1'b0;
      set_sensor <= {SW{1'b0}};
      set_axis <= 2'd0;
      set_value <= 16'd0;
      recapture <= 1'b0;
      accepted <= 16'd0;
      rejected <= 16'd0;
      last_type <= 8'd0;
      last_reason <= 8'd0;
      last_seq <= 8'd0;
      reject <= 1'b0;
    end else begin
      c_valid <= 1'b0;
      set_valid <= 1'b0;
      recapture <= 1'b0;
      t_valid <= 1'b0;
      reject <= 1'b0;
      case (state)
        S_HDR:
          if (pop) begin
            case (hidx)
              2'd0: typ <= head;
              2'd1: seq <= head;
              2'd2: len[7:0] <= head;
              default: len[15:8] <= head;
            endcase
            hidx <= hidx + 2'd1;
            if (hidx == 2'd3) begin
              got <= 16'd0;
              state <= ({head, len[7:0]} == 16'd0) ? S_EXEC : S_PAY;
            end
          end
        S_PAY:
          if (pop) begin
            if (got < 16'd12) pay[got[3:0]] <= head;
            got <= got + 16'd1;
            if (got + 16'd1 == len) state <= S_EXEC;
          end
        default: begin  // S_EXEC
          if (reason != 8'd0) begin
            rejected <= sat_inc(rejected);
            last_type <= typ;
            last_reason <= reason;
            last_seq <= seq;
            reject <= 1'b1;
          end else begin
            accepted <= sat_inc(accepted);
            c_valid <= is_c;
            c_row <= pay[0][2:0];
            c_col <= pay[1][3:0];
            c_value <= {pay[5], pay[4], pay[3], pay[2]};
            set_valid <= is_b;
            set_sensor <= pay[0][SW-1:0];
            set_axis <= pay[1][1:0];
            set_value <= {pay[3], pay[2]};
            recapture <= is_r;
            t_valid <= is_l;
            t_cell <= pay[0][CW-1:0];
            t_index <= pay[1][4:0];
            t_which <= pay[2][1:0];
            t_value <= {pay[6], pay[5], pay[4], pay[3]};
            if (is_d) begin
              dc_k1 <= {pay[1], pay[0]};
              dc_c1 <= {pay[5], pay[4], pay[3], pay[2]};
              dc_k2 <= {pay[7], pay[6]};
              dc_c2 <= {pay[11], pay[10], pay[9], pay[8]};
            end
          end
          hidx <= 2'd0;
          state <= S_HDR;
        end
      endcase
    end
  end
endmodule
`default_nettype wire
