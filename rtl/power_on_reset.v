`default_nettype none
// power_on_reset: the reset of a top on a board, active high and
// synchronous: held for the first 16 clocks after configuration (the
// registers' initial values are loaded by the bitstream, no reset pin
// needed) and while the button rst_n is low, synchronised by two flops,
// and for 15 clocks after it: a glitch on rst_n that the synchroniser
// catches for one clock still resets for 16 (the frame engine needs at
// least two reset clocks: its P register is cleared by the second).
module power_on_reset (
    input  wire clk,
    input  wire rst_n,   // active low (button)
    output reg  rst = 1'b1
);
  reg [3:0] por_cnt = 4'd0;
  reg [1:0] rst_sync = 2'b00;
  always @(posedge clk) begin
    rst_sync <= {rst_sync[0], rst_n};
    if (!rst_sync[1]) por_cnt <= 4'd0;
    else if (por_cnt != 4'hF) por_cnt <= por_cnt + 4'd1;
    rst <= (por_cnt != 4'hF) || !rst_sync[1];
  end
endmodule
`default_nettype wire
