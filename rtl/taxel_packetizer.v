`default_nettype none
// taxel_packetizer: a frame's taxel stream -> its TAXELS_DENSE (0x02) and
// TAXELS_SPARSE (0x03) packets, byte by byte into the output FIFO, as
// hls/taxel_packetizer.h (TaxelPacketizer::frame, FifoBytes) makes them:
// each packet as type, t u32 LE, len u16 LE, payload (the FIFO's format,
// which rtl/link_framer.v frames), dense first.
//
// Per frame: a header token (hdr_*: t, which of the two packets, the sparse
// threshold), then the frame's R x C taxels, row-major (in_value = g, with
// in_row, in_col for the sparse list, in_last on the last). The dense packet
// (rows, cols, g u16 LE ...) streams while the taxels come in, two bytes a
// taxel. The sparse packet's len (4 x the taxels with g >= max(1,
// sparse_min)) comes before its list, so its entries {row, col, g} are kept
// as they come (a RAM of T x 32 bits: block RAM at 64x64) and counted, and
// the packet follows the frame's last taxel. The next header is taken after
// the sparse packet's last byte.
//
// Whole packets or none, as the frame engine writes (docs/protocol.md
// section 4): a packet starts only when out_free (the FIFO's free bytes,
// rtl/byte_fifo.v) holds all of it (7 + len, plus the byte waiting in
// out_data); otherwise it is left out and `dropped` pulses for a clock (the
// top counts it in dropped_frames). A dense packet left out still lets its
// taxels through to the sparse list. rtl/list_packet_writer.v writes the
// sparse packet.
//
// Rate: one byte a clock on out_* from a packet's first byte to its last
// while out_ready is high; a taxel a clock in while no dense packet is
// written (two clocks a taxel while one is). Timing with every stream
// ready, in handshake edges (tests/rtl/taxel_packetizer_test.cpp checks
// it): the dense packet's first byte 2 edges after its frame's header,
// taxel k 10 + 2k after it; the sparse packet's first byte 2 edges after
// the dense packet's last (3 after the last taxel without one: the room
// check takes a clock); the next header 1 edge after the last byte (2
// after the last taxel of a frame with no packet). A frame with both
// packets thus holds the output for 7 + len_dense + 7 + len_sparse + 3
// clocks. out_data is stable while out_valid && !out_ready.
module taxel_packetizer #(
    parameter integer R = 3,   // rows, 1 .. 255 (a u8 in the packets)
    parameter integer C = 3    // columns, 1 .. 255; R C <= 16383 (sparse len u16)
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        hdr_valid,
    output wire        hdr_ready,
    input  wire [31:0] hdr_t,
    input  wire        hdr_dense,
    input  wire        hdr_sparse,
    input  wire [15:0] hdr_sparse_min,
    input  wire        in_valid,
    output reg         in_ready,
    input  wire [15:0] in_value,
    input  wire [7:0]  in_row,
    input  wire [7:0]  in_col,
    input  wire        in_last,
    input  wire [15:0] out_free,
    output reg         out_valid,
    input  wire        out_ready,
    output reg  [7:0]  out_data,
    output wire        dropped,
    output wire        idle
);
  localparam integer T = R * C;
  generate
    if (R < 1 || R > 255 || C < 1 || C > 255 || T > 16383) begin : g_bad_params
      taxel_packetizer_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  localparam integer AB = (T > 1) ? $clog2(T) : 1;  // list address bits
  localparam integer NB = $clog2(T + 1);            // list count bits
  localparam [15:0] DENSE_LEN = 16'(2 + 2 * T);
  localparam [16:0] DENSE_ROOM = 17'(7 + 2 + 2 * T);

  // S_SKIP: a frame without a sparse packet takes the clock its room check
  // would.
  localparam [1:0] S_IDLE = 2'd0, S_DHDR = 2'd1, S_TAX = 2'd2, S_SKIP = 2'd3;
  reg [1:0]  state;
  reg [3:0]  bidx;        // dense header byte
  reg [31:0] t;
  reg        dense_on, sparse_on, hi_next;
  reg [15:0] lo;          // max(1, sparse_min)
  reg [7:0]  hi_byte;
  reg [NB-1:0] n;         // entries in the list
  wire [AB-1:0] ridx;     // the list entry rd_q is read from
  reg        last_in;     // the frame's last taxel is in

  wire en = !out_valid || out_ready;
  wire w_idle;            // no sparse packet being checked or written
  assign hdr_ready = state == S_IDLE && w_idle && !out_valid;
  assign idle = hdr_ready;
  wire hdr_take = hdr_valid && hdr_ready;
  wire dense_room = {1'b0, out_free} >= DENSE_ROOM + {16'd0, out_valid};

  // The list of lit taxels (one write a clock while they come in, one
  // registered read a clock while the sparse packet goes out).
  reg [31:0] list [0:T-1];
  reg [31:0] rd_q;
  wire in_take = in_valid && in_ready;
  wire lit = sparse_on && in_value >= lo;
  always @(posedge clk) begin
    if (in_take && lit) list[n[AB-1:0]] <= {in_value, in_col, in_row};
    rd_q <= list[ridx];
  end

  // The frame's last taxel (its high byte, with a dense packet) leaves this
  // clock: the sparse packet's turn.
  wire frame_end = state == S_TAX && (dense_on ? (hi_next && en && last_in)
                                               : (in_take && in_last));
  // The sparse packet: its entries {row, col, g lo, g hi} as stored.
  wire       w_valid;
  wire [7:0] w_data;
  wire       w_dropped;
  list_packet_writer #(.TYPE(8'h03), .EB(4), .N(T)) u_writer (
      .clk(clk), .rst(rst),
      .start_valid(frame_end && sparse_on), .start_ready(w_idle),
      .t(t), .n(n), .out_free(out_free), .out_pending(out_valid),
      .rd_addr(ridx), .rd_q(rd_q),
      .byte_valid(w_valid), .byte_ready(en), .byte_data(w_data), .dropped(w_dropped));
  reg dense_dropped;
  assign dropped = dense_dropped || w_dropped;

  `include "fifo_packet_header.vh"
  // This clock's byte, if any.
  reg       emit;
  reg [7:0] byte_out;
  always @(*) begin
    emit = 1'b0;
    // The dense header: the FIFO's 7 bytes, then rows, cols.
    byte_out = (bidx == 4'd7) ? 8'(R)
             : bidx[3] ? 8'(C) : fifo_header_byte(bidx[2:0], 8'h02, t, DENSE_LEN);
    in_ready = 1'b0;
    case (state)
      S_DHDR: emit = en;
      S_TAX:
        if (!dense_on) begin
          in_ready = 1'b1;
        end else if (hi_next) begin
          emit = en;
          byte_out = hi_byte;
        end else begin
          in_ready = en;
          emit = in_valid && en;
          byte_out = in_value[7:0];
        end
      default:
        if (w_valid) begin
          emit = en;
          byte_out = w_data;
        end
    endcase
  end

  always @(posedge clk) begin
    if (rst) begin
      state <= S_IDLE;
      out_valid <= 1'b0;
      dense_dropped <= 1'b0;
      bidx <= 4'd0;
      hi_next <= 1'b0;
      last_in <= 1'b0;
      n <= {NB{1'b0}};
    end else begin
      dense_dropped <= 1'b0;
      if (en) begin
        out_valid <= emit;
        if (emit) out_data <= byte_out;
      end
      if (in_take) begin
        if (lit) n <= n + 1'b1;
        last_in <= in_last;
        if (dense_on) begin
          hi_next <= 1'b1;
          hi_byte <= in_value[15:8];
        end
      end
      case (state)
        S_IDLE:
          if (hdr_take) begin
            t <= hdr_t;
            sparse_on <= hdr_sparse;
            lo <= (hdr_sparse_min > 16'd1) ? hdr_sparse_min : 16'd1;
            n <= {NB{1'b0}};
            bidx <= 4'd0;
            hi_next <= 1'b0;
            dense_on <= hdr_dense && dense_room;
            dense_dropped <= hdr_dense && !dense_room;
            state <= (hdr_dense && dense_room) ? S_DHDR : S_TAX;
          end
        S_DHDR:
          if (en) begin
            bidx <= bidx + 4'd1;
            if (bidx == 4'd8) state <= S_TAX;
          end
        S_TAX: begin
          if (dense_on && hi_next && en) hi_next <= 1'b0;
          if (frame_end) state <= sparse_on ? S_IDLE : S_SKIP;
        end
        default: state <= S_IDLE;
      endcase
    end
  end
endmodule
`default_nettype wire
