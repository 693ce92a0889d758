`default_nettype none
// cmd_decoder: host command frames (bytes from uart_rx) -> a FIFO of whole,
// well-formed frames for the frame engine, which judges their contents
// (types, lengths, ranges: docs/protocol.md §5). Frame format: §3.
//
// Frames are COBS-decoded on the fly (the implied zero of a block is only
// emitted when the next block starts, so a frame's trailing block adds
// none). Each raw byte updates a CRC-16/CCITT-FALSE register (rtl/crc16.v);
// the frame's big-endian CRC makes it 0 at the end. The raw bytes except t
// (type, seq, len LE, payload, crc) are written to the FIFO as they arrive,
// tentatively. At the 0x00 delimiter the frame is judged:
//   1. structure: COBS block cut short, fewer than 10 raw bytes, raw length
//      != 10 + len, or a UART error (rx_error) during the frame
//      -> dropped, frame_errors + 1;
//   2. the FIFO ran out of room during the frame -> dropped, overflows + 1;
//   3. CRC register != 0 -> dropped, crc_errors + 1;
//   4. its type is not routed here (below) -> dropped, not counted: another
//      decoder on the same line takes it;
//   5. otherwise committed without its two CRC bytes: the engine reads
//      type, seq, len (2 bytes LE), then len payload bytes.
// Routing: a top sharing the host link with another (rtl/mixed_top.v) keeps
// only the command types in TYPE_LO..TYPE_HI (TYPE_IN = 1) or only those
// outside it (TYPE_IN = 0), so each command reaches exactly one top; the
// defaults keep every type. Broken frames are counted by every decoder that
// sees them (each top reports the line it listens to).
// A dropped frame's bytes are discarded (write pointer back to the last
// commit). Counters are 16-bit, saturating, zeroed by `clear`. Bytes are
// taken every clock (s_ready = 1).
// Reading: `avail` while a committed byte is there; `head` is that byte
// one clock after it became the head (block RAM); `pop` takes it.
module cmd_decoder #(
    parameter integer DEPTH = 512,  // FIFO bytes, power of two
    parameter [7:0] TYPE_LO = 8'h00,
    parameter [7:0] TYPE_HI = 8'hFF,
    parameter integer TYPE_IN = 1   // 1: keep TYPE_LO..TYPE_HI, 0: keep the others
) (
    input  wire       clk,
    input  wire       rst,
    input  wire       s_valid,
    output wire       s_ready,
    input  wire [7:0] s_data,
    input  wire       rx_error,     // uart_rx frame_err | overrun
    output wire       avail,
    output reg  [7:0] head,
    input  wire       pop,
    input  wire       clear,
    output reg [15:0] crc_errors,
    output reg [15:0] frame_errors,
    output reg [15:0] overflows
);
  localparam integer AW = $clog2(DEPTH);
  generate
    if (DEPTH < 16 || (1 << AW) != DEPTH || TYPE_LO > TYPE_HI || (TYPE_IN != 0 && TYPE_IN != 1)) begin : g_bad_params
      cmd_decoder_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate
  assign s_ready = 1'b1;

  // ---------------- COBS decoding ----------------
  reg [7:0]  code_rem;   // data bytes left in the current block
  reg        pend_zero;  // the current block's implied zero, if another block follows
  reg        in_frame;
  reg        bad;        // UART error inside this frame
  reg        ovf;        // FIFO full inside this frame
  reg [16:0] count;      // raw bytes (saturating)
  reg [3:0]  pos;        // the same, saturating at 15: the header's places
  reg [15:0] crc;
  reg [16:0] len10;      // the header's len + 10: the frame's raw bytes
  reg [7:0]  typ;        // the frame's first raw byte

  wire delim = s_valid && s_data == 8'd0;
  wire is_code = s_valid && !delim && code_rem == 8'd0;
  wire raw_en = s_valid && !delim && (!is_code || pend_zero);
  wire [7:0] raw = is_code ? 8'd0 : s_data;
  wire [15:0] crc_next;
  crc16 u_crc (.crc_in(crc), .data(raw), .crc_out(crc_next));

  // len + 10 is formed when len's high byte arrives, not here: the adder
  // off the delimiter's path (the UP5K's 8x8 build, 99.8 % full, placed
  // code_rem -> this check -> the error counters at 15-16 MHz).
  wire struct_ok = !bad && code_rem == 8'd0 && pos >= 4'd10 && count == len10;
  wire do_frame = delim && in_frame;
  // typ - TYPE_LO wraps below TYPE_LO, so one compare tests both ends.
  wire [7:0] typ_off = typ - TYPE_LO;
  wire routed_here;
  generate
    if (TYPE_LO == 8'h00 && TYPE_HI == 8'hFF) begin : g_all_types
      assign routed_here = TYPE_IN != 0;
      wire unused_typ = &{1'b0, typ_off};
    end else begin : g_type_range
      wire in_range = typ_off <= TYPE_HI - TYPE_LO;
      assign routed_here = (TYPE_IN != 0) ? in_range : !in_range;
    end
  endgenerate

  // ---------------- FIFO with commit / rollback ----------------
  reg [7:0] mem [0:DEPTH-1];
  reg [AW:0] wp, wc, rp;     // tentative write, committed write, read
  wire store = raw_en && (pos < 4'd2 || pos > 4'd5);  // not t
  wire full = (wp - rp) == DEPTH[AW:0];
  localparam [AW:0] TWO = 2;
  assign avail = (rp != wc) && !fresh;
  reg fresh;                 // head register not yet updated for rp
  always @(posedge clk) begin
    if (store && !full && !ovf) mem[wp[AW-1:0]] <= raw;
    head <= mem[rp[AW-1:0]];
  end

  function automatic [15:0] sat_inc(input [15:0] x);
    sat_inc = (x == 16'hFFFF) ? x : x + 16'd1;
  endfunction

  always @(posedge clk) begin
    if (rst) begin
      code_rem <= 8'd0;
      pend_zero <= 1'b0;
      in_frame <= 1'b0;
      bad <= 1'b0;
      ovf <= 1'b0;
      count <= 17'd0;
      pos <= 4'd0;
      crc <= 16'hFFFF;
      len10 <= 17'd0;
      typ <= 8'd0;
      wp <= {(AW + 1){1'b0}};
      wc <= {(AW + 1){1'b0}};
      rp <= {(AW + 1){1'b0}};
      fresh <= 1'b1;
      crc_errors <= 16'd0;
      frame_errors <= 16'd0;
      overflows <= 16'd0;
    end else begin
      fresh <= pop;
      if (pop && avail) rp <= rp + 1'b1;
      // A byte lost by the UART belongs to the frame being received (or
      // about to start): that frame cannot be trusted.
      if (rx_error) bad <= 1'b1;
      if (store) begin
        if (full || ovf) ovf <= 1'b1;
        else wp <= wp + 1'b1;
      end
      if (delim) begin
        code_rem <= 8'd0;
        pend_zero <= 1'b0;
        in_frame <= 1'b0;
        bad <= 1'b0;
        ovf <= 1'b0;
        count <= 17'd0;
        pos <= 4'd0;
        crc <= 16'hFFFF;
      end else if (s_valid) begin
        in_frame <= 1'b1;
        if (is_code) begin
          code_rem <= s_data - 8'd1;
          pend_zero <= (s_data != 8'hFF);
        end else begin
          code_rem <= code_rem - 8'd1;
        end
        if (raw_en) begin
          crc <= crc_next;
          if (count != 17'h1FFFF) count <= count + 17'd1;
          if (pos != 4'd15) pos <= pos + 4'd1;
          if (pos == 4'd0) typ <= raw;
          if (pos == 4'd6) len10[7:0] <= raw;
          if (pos == 4'd7) len10 <= {1'b0, raw, len10[7:0]} + 17'd10;
        end
      end
      if (do_frame) begin
        if (!struct_ok || ovf || crc != 16'd0 || !routed_here) begin
          wp <= wc;  // discard the frame
          if (!struct_ok) frame_errors <= sat_inc(frame_errors);
          else if (ovf) overflows <= sat_inc(overflows);
          else if (crc != 16'd0) crc_errors <= sat_inc(crc_errors);
        end else begin
          wc <= wp - TWO;  // without the CRC bytes
          wp <= wp - TWO;
        end
      end
      if (clear) begin
        crc_errors <= 16'd0;
        frame_errors <= 16'd0;
        overflows <= 16'd0;
      end
    end
  end
endmodule
`default_nettype wire
