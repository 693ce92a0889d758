// spike_encoder: spike tokens -> address-event words {t, layer, neuron}.
// Bit-exact implementation of hls/spike_encoder.h (word layout there):
// tokens without a spike are consumed and dropped. One register stage:
// LATENCY 1 (out_valid the cycle after the input handshake), II 1,
// in_ready = !out_valid || out_ready.
module spike_encoder #(
    parameter integer LAYER_W = 4,
    parameter integer ADDR_W = 12
) (
    input  wire                       clk,
    input  wire                       rst,
    input  wire                       in_valid,
    output wire                       in_ready,
    input  wire [LAYER_W-1:0]         in_layer,
    input  wire [ADDR_W-1:0]          in_neuron,
    input  wire [31:0]                in_t,
    input  wire                       in_spike,
    output reg                        out_valid,
    input  wire                       out_ready,
    output reg  [31+LAYER_W+ADDR_W:0] out_word
);
  assign in_ready = !out_valid || out_ready;
  always @(posedge clk) begin
    if (rst) out_valid <= 1'b0;
    else if (in_ready) begin
      out_valid <= in_valid && in_spike;
      if (in_valid && in_spike) out_word <= {in_t, in_layer, in_neuron};
    end
  end
endmodule
