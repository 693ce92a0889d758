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
`ifdef FORMAL
  // Properties (tests/formal/byte_fifo.sby, docs/formal.md). Inputs are
  // free, rst included, except that the first clock resets. One byte is
  // followed through: f_idx (any constant) names it by its write count
  // mod 2^(AW+1); the byte written as that one must come out as that one,
  // which for an arbitrary f_idx is order and data kept for every byte.
  reg f_past = 1'b0;
  always @(posedge clk) f_past <= 1'b1;
  always @(*) if (!f_past) assume (rst);

  // Independent counts: bytes accepted, bytes moved to the output
  // register, bytes refused while full (saturating like overflows).
  reg [AW:0] f_in, f_ld;
  reg [15:0] f_ovf;
  always @(posedge clk)
    if (rst) begin
      f_in <= 0;
      f_ld <= 0;
      f_ovf <= 0;
    end else begin
      if (in_valid && !full) f_in <= f_in + 1'b1;
      if (load) f_ld <= f_ld + 1'b1;
      if (in_valid && full && f_ovf != 16'hFFFF) f_ovf <= f_ovf + 16'd1;
    end
  wire [AW:0] f_held = f_in - f_ld;  // bytes in the RAM, counted apart
  always @(*)
    if (f_past && !rst) begin
      assert (used <= DEPTH[AW:0]);                   // no overflow of the RAM
      assert (wp == f_in && rp == f_ld);              // pointers are the counts
      assert ({1'b0, free} == 17'(DEPTH) - {{(16 - AW){1'b0}}, f_held});  // the free count exact
      assert (overflows == f_ovf);                    // every refused byte counted
    end

  (* anyconst *) reg [AW:0] f_idx;
  reg f_have;        // the followed byte is in the RAM or the output register
  reg [7:0] f_byte;
  wire f_in_ram = (f_idx - rp) < used;               // rp <= f_idx < wp
  wire f_in_out = out_valid && (rp - 1'b1 == f_idx);
  always @(posedge clk)
    if (rst) f_have <= 1'b0;
    else begin
      if (in_valid && !full && wp == f_idx) begin
        f_have <= 1'b1;
        f_byte <= in_data;
      end
      if (f_in_out && out_ready) f_have <= 1'b0;  // taken (and replaced, if load)
    end
  always @(*)
    if (f_past && !rst) begin
      if (f_have) assert (f_in_ram || f_in_out);
      if (f_in_ram) assert (f_have && mem[f_idx[AW-1:0]] == f_byte);
      if (f_in_out) assert (f_have && out_data == f_byte);   // order and data kept
    end

  // No underflow: the output register is only loaded from a written byte,
  // and a byte shown is held until taken.
  always @(posedge clk)
    if (f_past && !$past(rst) && !rst) begin
      if ($past(out_valid && !out_ready)) assert (out_valid && $stable(out_data));
      if ($rose(out_valid)) assert ($past(used) != 0);
    end

  always @(posedge clk)
    if (!rst) begin
      cover (f_past && full && in_valid);                 // a byte refused
      cover (f_past && f_in_out && out_ready && f_ld > DEPTH[AW:0]);  // a byte out after the pointers wrapped
      cover (f_past && used == DEPTH[AW:0] && out_valid && !out_ready);  // full, output stalled
    end
`endif
endmodule
`default_nettype wire
