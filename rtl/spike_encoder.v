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
// dropped_frames).
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
    output reg         dropped,
    output reg  [31:0] spikes_dropped
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

  localparam [1:0] S_CMD = 2'd0, S_CHK = 2'd1, S_HDR = 2'd2, S_PAY = 2'd3;
  reg [1:0]  state;
  reg        open;
  reg [31:0] t0;
  reg [15:0] t;          // the frame's t, mod 2^16 (all dt needs)
  reg [NB-1:0] n;        // events of the window
  reg [NB-1:0] ridx;     // the event rd_q is read from (up to MAX: none)
  reg [2:0]  bidx;       // header byte 0..6; event byte 0..4
  reg [32:0] ev;         // the event being sent: {neuron, layer, dt}

  wire en = !out_valid || out_ready;
  assign in_ready = state == S_CMD && !out_valid;
  wire take = in_valid && in_ready;
  wire [15:0] n16 = 16'(n);
  wire [15:0] len = {n16[13:0], 2'b00} + n16;  // 5 n, without a multiplier
  wire room = {1'b0, out_free} >= {1'b0, len} + 17'd7 + {16'd0, out_valid};

  reg [32:0] events [0:MAX-1];
  reg [32:0] rd_q;
  wire [15:0] dt = t - t0[15:0];
  wire store = take && in_op == OP_SPIKE && n != N_MAX;
  always @(posedge clk) begin
    if (store) events[n[AB-1:0]] <= {in_neuron, in_layer, dt};
    rd_q <= events[ridx[AB-1:0]];
  end

  reg       emit;
  reg [7:0] byte_out;
  always @(*) begin
    emit = 1'b0;
    byte_out = 8'd0;
    if (state == S_HDR) begin
      emit = en;
      case (bidx)
        3'd0: byte_out = 8'h04;
        3'd1: byte_out = t0[7:0];
        3'd2: byte_out = t0[15:8];
        3'd3: byte_out = t0[23:16];
        3'd4: byte_out = t0[31:24];
        3'd5: byte_out = len[7:0];
        default: byte_out = len[15:8];
      endcase
    end else if (state == S_PAY) begin
      emit = en;
      case (bidx)
        3'd0: byte_out = ev[7:0];
        3'd1: byte_out = ev[15:8];
        3'd2: byte_out = {7'd0, ev[16]};
        3'd3: byte_out = ev[24:17];
        default: byte_out = ev[32:25];
      endcase
    end
  end

  always @(posedge clk) begin
    if (rst) begin
      state <= S_CMD;
      open <= 1'b0;
      t0 <= 32'd0;
      t <= 16'd0;
      n <= {NB{1'b0}};
      ridx <= {NB{1'b0}};
      bidx <= 3'd0;
      out_valid <= 1'b0;
      dropped <= 1'b0;
      spikes_dropped <= 32'd0;
    end else begin
      dropped <= 1'b0;
      if (en) begin
        out_valid <= emit;
        if (emit) out_data <= byte_out;
      end
      case (state)
        S_CMD:
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
              OP_CLOSE: begin
                open <= 1'b0;
                if (n != {NB{1'b0}}) state <= S_CHK;
              end
              default: ;
            endcase
          end
        S_CHK: begin
          bidx <= 3'd0;
          ridx <= {NB{1'b0}};
          if (room) begin
            state <= S_HDR;
          end else begin
            dropped <= 1'b1;
            state <= S_CMD;
          end
        end
        S_HDR:
          if (en) begin
            bidx <= bidx + 3'd1;
            if (bidx == 3'd6) begin
              // rd_q has held event 0 since the header's first byte.
              ev <= rd_q;
              ridx <= NB'(1);
              bidx <= 3'd0;
              state <= S_PAY;
            end
          end
        S_PAY:
          if (en) begin
            bidx <= bidx + 3'd1;
            if (bidx == 3'd4) begin
              // rd_q = event ridx, read during this event's bytes.
              bidx <= 3'd0;
              ev <= rd_q;
              ridx <= ridx + 1'b1;
              if (ridx == n) state <= S_CMD;
            end
          end
        default: state <= S_CMD;
      endcase
    end
  end
endmodule
`default_nettype wire
