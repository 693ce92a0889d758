`default_nettype none
// list_packet_writer: one packet of a list into the output FIFO's format
// (the one rtl/link_framer.v frames): type TYPE, t u32 LE, len u16 LE (EB n),
// then the list's n entries of EB bytes each, entry 0 first, byte 0 of an
// entry first. The tail rtl/spike_encoder.v (SPIKES) and
// rtl/taxel_packetizer.v (TAXELS_SPARSE) share.
//
// Whole packets or none, as the frame engine writes: the clock after the
// start handshake checks that out_free (rtl/byte_fifo.v's free bytes) holds
// all 7 + EB n bytes plus out_pending (the byte the caller's output register
// still holds); if not, nothing is written and `dropped` pulses for a clock.
//
// The list stays in the caller's RAM, read one registered read at a time:
// rd_q must be entry rd_addr as it was the clock before (after the last
// entry rd_addr goes on to n, mod 2^AB: that read's value is not used). t
// and n are read while the packet goes out: the caller holds them from the
// start handshake until start_ready is high again (both callers take no new
// frame or window before then).
//
// Bytes leave on byte_valid/byte_ready into the caller's output register,
// which takes one when both are high; byte_valid does not depend on
// byte_ready. Timing, in edges from the start handshake: the room check at
// the next edge, the first byte offered from then on (taken at edge 2 at the
// earliest), then one byte an edge while byte_ready is high; start_ready
// again after the edge that takes the last byte (after the room check when
// the packet is left out).
module list_packet_writer #(
    parameter [7:0]   TYPE = 8'h00,  // the packet's type byte
    parameter integer EB = 4,        // bytes an entry: 2 .. 7 (an entry's bytes cover its next read)
    parameter integer N = 1          // entries at most: 1 .. 65535 / EB (len is a u16)
) (
    input  wire                       clk,
    input  wire                       rst,
    input  wire                       start_valid,
    output wire                       start_ready,
    input  wire [31:0]                t,
    input  wire [$clog2(N + 1) - 1:0] n,
    input  wire [15:0]                out_free,
    input  wire                       out_pending,
    output wire [((N > 1) ? $clog2(N) : 1) - 1:0] rd_addr,
    input  wire [8 * EB - 1:0]        rd_q,
    output wire                       byte_valid,
    input  wire                       byte_ready,
    output wire [7:0]                 byte_data,
    output reg                        dropped
);
  generate
    if (EB < 2 || EB > 7 || N < 1 || EB * N > 65535) begin : g_bad_params
      list_packet_writer_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  `include "fifo_packet_header.vh"

  localparam integer AB = (N > 1) ? $clog2(N) : 1;  // list address bits
  localparam integer NB = $clog2(N + 1);            // list count bits

  // EB x, by shifts and adds (EB is at most 7: three bits).
  function automatic [15:0] times_eb(input [15:0] x);
    integer b;
    begin
      times_eb = 16'd0;
      for (b = 0; b < 3; b = b + 1)
        if (((EB >> b) & 1) != 0) times_eb = times_eb + (x << b);
    end
  endfunction

  localparam [1:0] S_IDLE = 2'd0, S_CHK = 2'd1, S_HDR = 2'd2, S_PAY = 2'd3;
  reg [1:0]        state;
  reg [2:0]        bidx;  // header byte 0..6; entry byte 0..EB-1
  reg [8*EB-1:0]   ent;   // the entry being sent
  reg [NB-1:0]     ridx;  // the entry rd_q is read from (up to n: none)

  assign start_ready = state == S_IDLE;
  assign rd_addr = ridx[AB-1:0];
  wire [15:0] len = times_eb(16'(n));
  wire room = {1'b0, out_free} >= {1'b0, len} + 17'd7 + {16'd0, out_pending};

  reg [7:0] pay_byte;
  integer k;
  always @(*) begin
    pay_byte = ent[8 * (EB - 1) +: 8];
    for (k = 0; k < EB - 1; k = k + 1)
      if (bidx == 3'(k)) pay_byte = ent[8 * k +: 8];
  end
  assign byte_valid = state == S_HDR || state == S_PAY;
  assign byte_data = (state == S_HDR) ? fifo_header_byte(bidx, TYPE, t, len) : pay_byte;

  always @(posedge clk) begin
    if (rst) begin
      state <= S_IDLE;
      bidx <= 3'd0;
      ridx <= {NB{1'b0}};
      dropped <= 1'b0;
    end else begin
      dropped <= 1'b0;
      case (state)
        S_IDLE:
          if (start_valid) state <= S_CHK;
        S_CHK: begin
          bidx <= 3'd0;
          ridx <= {NB{1'b0}};
          if (room) begin
            state <= S_HDR;
          end else begin
            dropped <= 1'b1;
            state <= S_IDLE;
          end
        end
        S_HDR:
          if (byte_ready) begin
            bidx <= bidx + 3'd1;
            if (bidx == 3'd6) begin
              // rd_q has held entry 0 since the header's first byte.
              ent <= rd_q;
              ridx <= NB'(1);
              bidx <= 3'd0;
              state <= (n == {NB{1'b0}}) ? S_IDLE : S_PAY;
            end
          end
        S_PAY:
          if (byte_ready) begin
            bidx <= bidx + 3'd1;
            if (bidx == 3'(EB - 1)) begin
              // rd_q = entry ridx, read during this entry's bytes.
              bidx <= 3'd0;
              ent <= rd_q;
              ridx <= ridx + 1'b1;
              if (ridx == n) state <= S_IDLE;
            end
          end
        default: state <= S_IDLE;
      endcase
    end
  end
endmodule
`default_nettype wire
