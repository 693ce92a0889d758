// synapse_weights: weighted spike sums for the second spiking layer.
// Bit-exact implementation of hls/synapse_weights.h (formats, saturation and
// timing are stated there): collects one step of first-layer tokens into a
// spike-bit vector, then for each postsynaptic neuron i reads W[i][0..N_IN-1]
// from block RAM (row-major, one weight per cycle) and adds the weights of
// the neurons that spiked (no multiplier: s_j is 0 or 1); the sum saturates
// to signed OUT_W bits and leaves sign-extended to 32 bits.
// Resources (yosys synth_ice40 -dsp): 9 x 9: 174 LUT4, 1 SB_RAM40_4K;
// 256 x 16: 816 LUT4, 16 SB_RAM40_4K. A full 256 x 256 table (1 Mbit) does
// not fit the UP5K's 30 block RAMs: it would need all four SPRAMs.
module synapse_weights #(
    parameter integer N_IN = 9,
    parameter integer N_OUT = 9,
    parameter integer OUT_W = 16
) (
    input  wire          clk,
    input  wire          rst,
    // first-layer tokens (izhikevich_layer out)
    input  wire          in_valid,
    output wire          in_ready,
    input  wire [15:0]   in_neuron,
    input  wire [31:0]   in_t,
    input  wire          in_spike,
    input  wire          in_last,
    // second-layer input tokens (izhikevich_layer in)
    output reg           out_valid,
    input  wire          out_ready,
    output reg  [31:0]   out_x,
    output reg  [31:0]   out_t,
    output reg           out_last,
    // weight table write port: W[cfg_addr] = cfg_data, cfg_addr = i * N_IN + j
    input  wire          cfg_we,
    input  wire [WA-1:0] cfg_addr,
    input  wire [15:0]   cfg_data
);
  localparam integer NW = N_IN * N_OUT;
  localparam integer WA = NW > 1 ? $clog2(NW) : 1;
  localparam integer JW = N_IN > 1 ? $clog2(N_IN) : 1;
  localparam integer IW = N_OUT > 1 ? $clog2(N_OUT) : 1;
  localparam integer ACC_W = 16 + $clog2(N_IN + 1);
  // The sum always fits ACC_W bits; saturate only when OUT_W is narrower.
  localparam integer SW = OUT_W < ACC_W ? OUT_W : ACC_W;
  localparam signed [63:0] SAT_MAX64 = (64'sd1 <<< (SW - 1)) - 64'sd1;
  localparam signed [63:0] SAT_MIN64 = -(64'sd1 <<< (SW - 1));
  localparam signed [ACC_W-1:0] SAT_MAX = SAT_MAX64[ACC_W-1:0];
  localparam signed [ACC_W-1:0] SAT_MIN = SAT_MIN64[ACC_W-1:0];
  localparam [15:0] N_IN16 = N_IN[15:0];
  localparam [JW:0] J_END = N_IN[JW:0];
  localparam integer N_OUT_M1 = N_OUT - 1;
  localparam [IW-1:0] I_LAST = N_OUT_M1[IW-1:0];

  // ---- weight memory (block RAM: one write port, one registered read) ----
  reg [15:0] wmem[0:NW-1];
  reg [15:0] rdata;
  reg [WA-1:0] raddr;
  integer k;
  initial for (k = 0; k < NW; k = k + 1) wmem[k] = 16'd0;
  always @(posedge clk) begin
    if (cfg_we) wmem[cfg_addr] <= cfg_data;
    rdata <= wmem[raddr];
  end

  localparam [1:0] S_COLLECT = 2'd0, S_ACC = 2'd1, S_EMIT = 2'd2;
  reg [1:0] state;
  reg [N_IN-1:0] sbits;
  reg [JW:0] j;          // next weight of the row to read (0..N_IN)
  reg [IW-1:0] i;        // output neuron
  reg pend, s_pend;      // a read was issued last cycle; its spike bit
  reg signed [ACC_W-1:0] acc;
  assign in_ready = state == S_COLLECT;

  wire signed [15:0] w_s = rdata;
  wire signed [ACC_W-1:0] w_ext = {{(ACC_W - 16){w_s[15]}}, w_s};
  wire signed [ACC_W-1:0] term = (pend && s_pend) ? w_ext : {ACC_W{1'b0}};
  wire signed [ACC_W-1:0] total = acc + term;
  wire signed [ACC_W-1:0] sat = (total > SAT_MAX) ? SAT_MAX : (total < SAT_MIN) ? SAT_MIN : total;
  wire signed [31:0] sat32 = {{(32 - ACC_W){sat[ACC_W-1]}}, sat};

  always @(posedge clk) begin
    if (rst) begin
      state <= S_COLLECT;
      sbits <= {N_IN{1'b0}};
      out_valid <= 1'b0;
      pend <= 1'b0;
    end else begin
      case (state)
        S_COLLECT: if (in_valid) begin
          if (in_spike && in_neuron < N_IN16) sbits[in_neuron[JW-1:0]] <= 1'b1;
          out_t <= in_t;
          if (in_last) begin
            state <= S_ACC;
            raddr <= {WA{1'b0}};
            i <= {IW{1'b0}};
            j <= {(JW + 1){1'b0}};
            acc <= {ACC_W{1'b0}};
            pend <= 1'b0;
          end
        end
        S_ACC: begin
          acc <= total;
          if (j != J_END) begin  // issue the read of W[i][j]
            pend <= 1'b1;
            s_pend <= sbits[j[JW-1:0]];
            raddr <= raddr + 1'b1;
            j <= j + 1'b1;
          end else begin  // all N_IN terms in: emit
            pend <= 1'b0;
            out_x <= sat32;
            out_last <= i == I_LAST;
            out_valid <= 1'b1;
            state <= S_EMIT;
          end
        end
        default: if (out_ready) begin  // S_EMIT
          out_valid <= 1'b0;
          acc <= {ACC_W{1'b0}};
          j <= {(JW + 1){1'b0}};
          if (out_last) begin
            sbits <= {N_IN{1'b0}};
            state <= S_COLLECT;
          end else begin
            i <= i + 1'b1;
            state <= S_ACC;
          end
        end
      endcase
    end
  end
endmodule
