`default_nettype none
// spike_encoder: the spike windows of hls/spike_encoder.h as a streaming
// block, writing each window's SPIKES (0x04) packet into the output FIFO as
// SpikeEncoder::close_packet makes it: type, t u32 LE (the window's first
// frame), len u16 LE (5 n), then n events {dt u16 LE, layer u8, neuron u16
// LE} (the FIFO's format, which rtl/link_framer.v frames).
//
// In: one command a clock, the kernel's calls in order (in_op):
//   OP_FRAME  frame(in_t): a window opens at the first frame after a close
//             (t0 = t, n = 0); the frame's t is every later event's t
//   OP_SPIKE  spike(in_layer, in_neuron): event n, dt = t - t0 (mod 2^16),
//             while n < MAX; later ones are counted in spikes_dropped,
//             saturating at 65535 as the kernel's (the STATUS packet's u16
//             field, docs/protocol.md)
//   OP_CLOSE  close: the window's packet, when it holds events
// The caller keeps the kernel's order: within a frame layer 0's spikes in
// neuron order, then layer 1's (the two layers' streams meet before this
// block). The events are kept in a RAM of MAX x 33 bits (one block RAM at
// MAX 256) and sent after the close.
//
// Whole packets or none, as the frame engine writes: the packet starts only
// when out_free (rtl/byte_fifo.v's) holds its 7 + 5 n bytes plus the byte
// waiting in out_data; otherwise `dropped` pulses for a clock (the top's
// dropped_frames). rtl/list_packet_writer.v writes it.
//
// Rate: a command a clock (in_ready high) except while a packet goes out;
// the packet's first byte 2 edges after the close's handshake (the room
// check takes a clock), then one byte a clock while out_ready is high; the
// next command 1 edge after its last byte. out_data is stable while
// out_valid && !out_ready.
module spike_encoder #(
    parameter integer MAX = 256   // events a window: 1 .. 13107 (5 MAX bytes fit a u16 len)
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [1:0]  in_op,
    input  wire [31:0] in_t,
    input  wire        in_layer,
    input  wire [15:0] in_neuron,
    input  wire [15:0] out_free,
    output reg         out_valid,
    input  wire        out_ready,
    output reg  [7:0]  out_data,
    output wire        dropped,
    output reg  [31:0] spikes_dropped,
    input  wire        clear   // zero spikes_dropped (the top's CLEAR_COUNTERS)
);
  generate
    if (MAX < 1 || MAX > 13107) begin : g_bad_params
      spike_encoder_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  localparam [1:0] OP_FRAME = 2'd0, OP_SPIKE = 2'd1, OP_CLOSE = 2'd2;
  localparam integer AB = (MAX > 1) ? $clog2(MAX) : 1;  // event address bits
  localparam integer NB = $clog2(MAX + 1);              // event count bits
  localparam [NB-1:0] N_MAX = NB'(MAX);

  reg        open;
  reg [31:0] t0;
  reg [15:0] t;          // the frame's t, mod 2^16 (all dt needs)
  reg [NB-1:0] n;        // events of the window
  wire [AB-1:0] ridx;    // the event rd_q is read from

  wire en = !out_valid || out_ready;
  wire w_idle;           // no packet being checked or written
  assign in_ready = w_idle && !out_valid;
  wire take = in_valid && in_ready;

  reg [32:0] events [0:MAX-1];
  reg [32:0] rd_q;
  wire [15:0] dt = t - t0[15:0];
  wire store = take && in_op == OP_SPIKE && n != N_MAX;
  always @(posedge clk) begin
    if (store) events[n[AB-1:0]] <= {in_neuron, in_layer, dt};
    rd_q <= events[ridx];
  end

  // The window's packet: 5 bytes an event {dt u16 LE, layer u8, neuron u16
  // LE} out of the stored {neuron, layer, dt}.
  wire       w_valid;
  wire [7:0] w_data;
  list_packet_writer #(.TYPE(8'h04), .EB(5), .N(MAX)) u_writer (
      .clk(clk), .rst(rst),
      .start_valid(take && in_op == OP_CLOSE && n != {NB{1'b0}}), .start_ready(w_idle),
      .t(t0), .n(n), .out_free(out_free), .out_pending(out_valid),
      .rd_addr(ridx), .rd_q({rd_q[32:17], 7'd0, rd_q[16:0]}),
      .byte_valid(w_valid), .byte_ready(en), .byte_data(w_data), .dropped(dropped));

  always @(posedge clk) begin
    if (rst) begin
      open <= 1'b0;
      t0 <= 32'd0;
      t <= 16'd0;
      n <= {NB{1'b0}};
      out_valid <= 1'b0;
      spikes_dropped <= 32'd0;
    end else begin
      if (en) begin
        out_valid <= w_valid;
        if (w_valid) out_data <= w_data;
      end
      if (take) begin
        case (in_op)
          OP_FRAME: begin
            if (!open) begin
              open <= 1'b1;
              t0 <= in_t;
              n <= {NB{1'b0}};
            end
            t <= in_t[15:0];
          end
          OP_SPIKE:
            if (n != N_MAX) n <= n + 1'b1;
            else if (spikes_dropped != 32'hFFFF) spikes_dropped <= spikes_dropped + 32'd1;
          OP_CLOSE: open <= 1'b0;
          default: ;
        endcase
      end
      if (clear) spikes_dropped <= 32'd0;  // (over a drop in the same clock)
    end
  end
endmodule
`default_nettype wire
