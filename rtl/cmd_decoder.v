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
`ifdef FORMAL
  // Properties (tests/formal/cmd_decoder.sby, docs/formal.md). Inputs are
  // free (s_valid, s_data, rx_error, pop, clear, rst) except that the first
  // clock resets. A reference monitor decodes the same byte stream on its
  // own (COBS, its own bit-serial CRC, length, type range, FIFO room) and
  // the decoder's state, counters and commit pointer must agree with it;
  // one byte of one frame (f_k: any FIFO offset within a frame, f_pick: any
  // frame) is followed from the line to `head`.
  reg f_past = 1'b0;
  always @(posedge clk) f_past <= 1'b1;
  always @(*) if (!f_past) assume (rst);

  `include "formal_crc16.vh"  // the reference CRC, bit by bit

  // The reference's COBS decode: a code byte opens a block of code - 1 data
  // bytes; the zero implied by a code below 0xFF is a raw byte only when
  // another block follows in the frame.
  reg        f_in, f_pend, f_err, f_ovf, f_follow, f_kst, f_cm;
  reg [7:0]  f_rem, f_typ, f_kb;
  reg [16:0] f_n;                 // raw bytes of the frame (saturating)
  reg [15:0] f_crc, f_len;
  reg [AW:0] f_wc, f_fs, f_ca;    // committed bytes, this frame's stored bytes, followed byte's place
  reg [15:0] f_fe, f_ov, f_ce;    // the counters, counted apart
  (* anyconst *) reg [16:0] f_k;  // followed byte: offset in its frame's FIFO bytes
  (* anyseq *) reg f_pick;        // follow the frame starting now
  wire f_byte = s_valid && s_data != 8'd0;
  wire f_delim = s_valid && s_data == 8'd0;
  wire f_code = f_byte && f_rem == 8'd0;
  wire f_raw_en = f_byte && (f_rem != 8'd0 || f_pend);
  wire [7:0] f_raw = (f_rem != 8'd0) ? s_data : 8'd0;
  wire f_store = f_raw_en && (f_n < 17'd2 || f_n > 17'd5);  // type, seq, len, payload, crc
  wire [16:0] f_off = (f_n < 17'd2) ? f_n : f_n - 17'd4;      // its FIFO offset in the frame
  wire [AW:0] f_used = (f_wc - rp) + f_fs;
  wire f_room = f_used != DEPTH[AW:0];
  wire f_typ_in = f_typ >= TYPE_LO && f_typ <= TYPE_HI;
  wire f_routed = (TYPE_IN != 0) ? f_typ_in : !f_typ_in;
  wire [16:0] f_len10 = {1'b0, f_len} + 17'd10;
  wire f_struct = !f_err && f_rem == 8'd0 && f_n >= 17'd10 && f_n == f_len10;
  wire f_end = f_delim && f_in;
  wire f_commit = f_end && f_struct && !f_ovf && f_crc == 16'd0 && f_routed;
  wire [AW:0] f_flen = f_len[AW:0] + 3'd4;   // type, seq, len, payload
  wire f_read = pop && avail;
  // The bytes of this frame the FIFO should hold: type, seq, then all but t.
  wire [16:0] f_stored = (f_n < 17'd2) ? f_n : (f_n < 17'd6) ? 17'd2 : f_n - 17'd4;

  always @(posedge clk)
    if (rst) begin
      f_in <= 1'b0; f_pend <= 1'b0; f_err <= 1'b0; f_ovf <= 1'b0;
      f_rem <= 8'd0; f_n <= 17'd0; f_crc <= 16'hFFFF;
      f_wc <= 0; f_fs <= 0;
      f_fe <= 16'd0; f_ov <= 16'd0; f_ce <= 16'd0;
      f_follow <= 1'b0; f_kst <= 1'b0; f_cm <= 1'b0;
    end else begin
      // A UART error belongs to the frame in progress or the next one; one
      // in the very clock of a delimiter is not seen (uart_rx never pulses
      // an error in the clock it delivers a byte: the byte is dropped).
      if (rx_error) f_err <= 1'b1;
      if (f_read && rp == f_ca && f_cm) f_cm <= 1'b0;
      if (f_delim) begin
        f_in <= 1'b0; f_pend <= 1'b0; f_err <= 1'b0; f_ovf <= 1'b0;
        f_rem <= 8'd0; f_n <= 17'd0; f_crc <= 16'hFFFF; f_fs <= 0;
        f_follow <= 1'b0; f_kst <= 1'b0;
        if (f_end) begin
          if (f_commit) begin
            f_wc <= f_wc + f_flen;
            if (f_follow && f_k < {1'b0, f_len} + 17'd4) begin
              f_cm <= 1'b1;
              f_ca <= f_wc + f_k[AW:0];
            end
          end else if (!f_struct) f_fe <= (f_fe == 16'hFFFF) ? f_fe : f_fe + 16'd1;
          else if (f_ovf) f_ov <= (f_ov == 16'hFFFF) ? f_ov : f_ov + 16'd1;
          else if (f_crc != 16'd0) f_ce <= (f_ce == 16'hFFFF) ? f_ce : f_ce + 16'd1;
        end
      end else if (f_byte) begin
        f_in <= 1'b1;
        if (f_code) begin
          f_rem <= s_data - 8'd1;
          f_pend <= s_data != 8'hFF;
        end else f_rem <= f_rem - 8'd1;
        if (f_raw_en) begin
          f_crc <= f_crc16(f_crc, f_raw);
          if (f_n != 17'h1FFFF) f_n <= f_n + 17'd1;
          if (f_n == 17'd0) begin
            f_typ <= f_raw;
            f_follow <= f_pick && !f_cm;
          end
          if (f_n == 17'd6) f_len[7:0] <= f_raw;
          if (f_n == 17'd7) f_len[15:8] <= f_raw;
          if (f_store) begin
            // Room: the committed bytes not yet read plus this frame's.
            if (f_ovf || !f_room) f_ovf <= 1'b1;
            else begin
              f_fs <= f_fs + 1'b1;
              if ((f_n == 17'd0 ? f_pick && !f_cm : f_follow) && f_off == f_k) begin
                f_kst <= 1'b1;
                f_kb <= f_raw;
              end
            end
          end
        end
      end
      if (clear) begin
        f_fe <= 16'd0; f_ov <= 16'd0; f_ce <= 16'd0;
      end
    end

  always @(*)
    if (f_past && !rst) begin
      // The decoder's decisions are the reference's: what it committed
      // (wc: exactly len + 4 bytes per accepted frame, nothing for a rejected
      // one) and each rejection counted once, by its first reason.
      assert (wc == f_wc);
      assert (frame_errors == f_fe && overflows == f_ov && crc_errors == f_ce);
      // The same frame state (needed for induction; also: after any
      // delimiter everything is back to idle, since the reference is).
      assert (in_frame == f_in && code_rem == f_rem && pend_zero == f_pend);
      assert (bad == f_err && ovf == f_ovf && crc == f_crc && count == f_n);
      assert (pos == ((f_n > 17'd15) ? 4'd15 : f_n[3:0]));
      if (f_n >= 17'd1) assert (typ == f_typ);
      if (f_n == 17'd7) assert (len10[7:0] == f_len[7:0]);
      if (f_n >= 17'd8) assert (len10 == f_len10);
      if (!f_in) assert (f_n == 17'd0 && !f_pend && f_rem == 8'd0 && !f_ovf);
      // The FIFO: committed bytes, then this frame's, never over DEPTH.
      assert (wp == f_wc + f_fs);
      assert ((wc - rp) <= DEPTH[AW:0] && f_used <= DEPTH[AW:0]);
      assert ({1'b0, f_wc - rp} + {1'b0, f_fs} <= {1'b0, DEPTH[AW:0]});  // without wrapping
      // The followed byte: in the RAM from its write until it is read.
      if (f_kst) assert (f_follow && f_k < {{(16 - AW){1'b0}}, f_fs} && mem[f_wc[AW-1:0] + f_k[AW-1:0]] == f_kb);
      if (f_follow && !f_kst) assert (f_k >= {{(16 - AW){1'b0}}, f_fs} || f_ovf);
      if (f_follow) assert (!f_cm);
      if (f_cm) assert (((f_ca - rp) < (wc - rp)) && mem[f_ca[AW-1:0]] == f_kb);
      if (avail) assert (head == mem[rp[AW-1:0]]);
      // This frame's stored bytes: type, seq, then all but t (until full).
      if (!f_ovf) assert ({{(16 - AW){1'b0}}, f_fs} == f_stored);
      else assert ({{(16 - AW){1'b0}}, f_fs} < f_stored);
      if (f_n == 17'd0) assert (!f_kst && !f_ovf && !f_follow);
    end

  // Delivered whole and once: a committed frame's byte f_k is the one its
  // raw byte (type, seq, len LE, payload; never t or the CRC) carried, and
  // `head` shows it when it is popped.
  always @(posedge clk)
    if (f_past && !rst) begin
      if (f_commit && f_follow && f_k < {1'b0, f_len} + 17'd4) assert (f_kst);
      if (f_cm && f_read && rp == f_ca) assert (head == f_kb);
    end
  always @(posedge clk)
    if (f_past && !rst && $past(f_past && !rst && f_delim)) begin
      // After any delimiter: idle, whatever came before.
      assert (!in_frame && code_rem == 8'd0 && !pend_zero && !bad && !ovf);
      assert (count == 17'd0 && pos == 4'd0 && crc == 16'hFFFF);
    end
  // Each decision is reachable.
  reg f_rejected;  // a frame was rejected since reset
  always @(posedge clk)
    if (rst) f_rejected <= 1'b0;
    else if (f_end && !f_commit) f_rejected <= 1'b1;
  always @(posedge clk)
    if (f_past && !rst) begin
      cover (f_commit && f_len != 16'd0);                  // a command with a payload committed
      cover (f_commit && f_rejected);                      // a good one after a rejected one
      cover (f_end && !f_struct);                          // a frame error
      cover (f_end && f_struct && f_ovf);                  // an overflow
      cover (f_end && f_struct && !f_ovf && f_crc != 16'd0);  // a CRC error
      cover (f_end && f_struct && !f_ovf && f_crc == 16'd0 && !f_routed);  // another top's
      cover (f_cm && f_read && rp == f_ca);                // the followed byte popped
    end
`endif
endmodule
`default_nettype wire
