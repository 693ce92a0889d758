// tag_fifo: a tiny register FIFO that carries a side tag (the 32-bit sample
// counter t of a frame) past a pipeline stage whose token stream has no room
// for it. The owner pushes the tag when a frame enters the stage and pops it
// when the frame's last token leaves; the head is the tag of the frame at the
// stage's output. DEPTH must cover the frames a stage holds at once (2 for
// sdft_bank: one finishing in its output register, one being computed; 1 for
// carrier_magnitude and taxel_reconstruct, which take no input while their
// output is pending, and whose next frame is pushed after the pop). Pushing into a full FIFO or popping an empty one is a
// design error: `error` latches it (the system test asserts it stays 0).
module tag_fifo #(
    parameter integer W = 32,
    parameter integer DEPTH = 2   // 1, or a power of two
) (
    input  wire         clk,
    input  wire         rst,
    input  wire         push,
    input  wire [W-1:0] push_tag,
    input  wire         pop,
    output wire [W-1:0] head,
    output reg          error
);
  generate
    if (DEPTH == 1) begin : g_reg
      // One tag: a register and an occupancy bit.
      reg [W-1:0] tag;
      reg full;
      assign head = tag;
      always @(posedge clk) begin
        if (push) tag <= push_tag;
        if (rst) begin
          full <= 1'b0;
          error <= 1'b0;
        end else begin
          if (push != pop) full <= push;
          if ((push && !pop && full) || (pop && !full)) error <= 1'b1;
        end
      end
    end else begin : g_fifo
      localparam integer AW = $clog2(DEPTH);
      reg [W-1:0] mem [0:DEPTH-1];
      reg [AW:0] count;
      reg [AW-1:0] rp, wp;
      assign head = mem[rp];
      always @(posedge clk) begin
        if (rst) begin
          count <= {(AW + 1){1'b0}};
          rp <= {AW{1'b0}};
          wp <= {AW{1'b0}};
          error <= 1'b0;
        end else begin
          if (push) begin
            mem[wp] <= push_tag;
            wp <= wp + 1'b1;
          end
          if (pop) rp <= rp + 1'b1;
          if (push && !pop) count <= count + 1'b1;
          if (pop && !push) count <= count - 1'b1;
          if ((push && !pop && count == DEPTH[AW:0]) || (pop && count == {(AW + 1){1'b0}}))
            error <= 1'b1;
        end
      end
    end
  endgenerate
endmodule
