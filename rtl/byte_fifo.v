`default_nettype none
// byte_fifo: the frame engine's output queue to link_framer, one block RAM.
// The writer (the engine's `out` to the output port) never waits: it checks
// `free` for a whole packet first and writes only then; a byte written while
// full is dropped and counted in `overflows` (a protocol error of the writer:
// the packet would be cut). The reader gets a first-word-fall-through
// valid/ready stream: out_data is stable while out_valid && !out_ready.
// `free` = DEPTH minus the bytes in the RAM (the output register's byte
// is not counted: conservative by one).
module byte_fifo #(
    parameter integer DEPTH = 512   // power of two
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        in_valid,
    input  wire [7:0]  in_data,
    output reg         out_valid,
    input  wire        out_ready,
    output reg  [7:0]  out_data,
    output wire [15:0] free,
    output reg  [15:0] overflows
);
  localparam integer AW = $clog2(DEPTH);
  generate
    if (DEPTH < 2 || DEPTH > 32768 || (1 << AW) != DEPTH) begin : g_bad_params
      byte_fifo_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  reg [7:0] mem [0:DEPTH-1];
  reg [AW:0] wp, rp;
  wire [AW:0] used = wp - rp;
  wire [AW:0] free_w = DEPTH[AW:0] - used;
  assign free = {{(15 - AW){1'b0}}, free_w};
  wire full = used == DEPTH[AW:0];
  wire load = (used != {(AW + 1){1'b0}}) && (!out_valid || out_ready);

  always @(posedge clk) begin
    if (in_valid && !full) mem[wp[AW-1:0]] <= in_data;
    if (load) out_data <= mem[rp[AW-1:0]];
  end

  always @(posedge clk) begin
    if (rst) begin
      wp <= {(AW + 1){1'b0}};
      rp <= {(AW + 1){1'b0}};
      out_valid <= 1'b0;
      overflows <= 16'd0;
    end else begin
      if (in_valid) begin
        if (!full) wp <= wp + 1'b1;
        else if (overflows != 16'hFFFF) overflows <= overflows + 16'd1;
      end
      if (load) begin
        rp <= rp + 1'b1;
        out_valid <= 1'b1;
      end else if (out_ready) begin
        out_valid <= 1'b0;
      end
    end
  end
endmodule
`default_nettype wire
