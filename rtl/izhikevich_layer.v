// izhikevich_layer: N Izhikevich neurons, one update per input token,
// time-multiplexed in address order over one 16x16 signed multiplier
// (SB_MAC16), state (v, U) in one N x 64 block RAM.
// Bit-exact implementation of hls/izhikevich_layer.h: number formats,
// saturation points and overflow proofs are stated there. The parameters
// are the fields of eskin::hls::IzhikevichConfig (make_izhikevich_config()
// computes them; defaults: RA receptor, dt = 1/35 ms, taxel g in UQ1.15,
// input_scale 10, x_shift 1).
//
// Streams (valid/ready): in {in_x signed 32, in_t}: the next neuron's input
// for this step; out {neuron, t, spike, last}: one token per input token.
// Timing: after reset N cycles of state initialisation (in_ready low); then
// input handshake in cycle 0, eight multiplies in cycles 1..8, out_valid
// from cycle 11 (LATENCY 11); in_ready again the cycle after the output
// handshake: II = 12 cycles per neuron with an always-ready output, so a
// layer step takes 12 N cycles (9 neurons: 108 of the 342 cycles of one
// 35 kHz sample at 12 MHz; 256 neurons: 3072 cycles, i.e. one step per
// 9 samples at 12 MHz (dt = 9/35 ms) or one per sample at >= 108 MHz).
// Resources (yosys synth_ice40 -dsp, Yosys 0.23): N = 9: 1011 LUT4,
// N = 256: 1013 LUT4; both 1 SB_MAC16, 4 SB_RAM40_4K (the 64-bit state word needs four
// 16-bit-wide blocks whatever N <= 256).
module izhikevich_layer #(
    parameter integer N = 9,
    parameter integer V_INIT = -272629760,   // v0 = -65 mV, Q9.22
    parameter integer U_INIT = -60445913,    // k b v0, Q.U_FRAC
    parameter integer V_RESET = -230686720,  // c = -55 mV
    parameter integer U_JUMP = 185987,       // k d, Q.U_FRAC
    parameter integer U_FRAC = 27,
    parameter integer C_CONST = -1888935,    // -16.25 k, Q9.22
    parameter integer M2 = 18599,            // c2 = 0.04 k
    parameter integer S2 = 16,
    parameter integer M3 = 16494,            // c3 = k^2 a b
    parameter integer S3 = 13,
    parameter integer M4 = 18599,            // c4 = k a
    parameter integer S4 = 25,
    parameter integer GAIN = 20433,          // J per xs LSB
    parameter integer GAIN_SHIFT = 5,
    parameter integer X_SHIFT = 1
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [31:0] in_x,
    input  wire [31:0] in_t,
    output reg         out_valid,
    input  wire        out_ready,
    output reg  [15:0] out_neuron,
    output reg  [31:0] out_t,
    output reg         out_spike,
    output reg         out_last,
    // The neuron's state after this update (v Q9.22, U Q.U_FRAC): for
    // verification and monitoring; costs no logic (the RAM write register).
    output wire [31:0] out_v,
    output wire [31:0] out_u
);
  localparam integer FRAC = 22;
  localparam signed [35:0] V_PEAK = 36'sd30 <<< FRAC;
  localparam signed [35:0] V_MIN = -(36'sd1 <<< 29);
  localparam signed [31:0] W_OFFSET = 32'sd125 <<< (FRAC - 1);  // 62.5 mV
  localparam signed [35:0] U_MAX = (36'sd1 <<< 30) - 36'sd1;
  localparam signed [35:0] U_MIN = -(36'sd1 <<< 30);
  localparam integer US = U_FRAC - FRAC;  // U -> Q.22 shift
  localparam integer GSR = GAIN_SHIFT >= 0 ? GAIN_SHIFT : 0;  // right shift of J
  localparam integer GSL = GAIN_SHIFT < 0 ? -GAIN_SHIFT : 0;  // left shift of J
  localparam integer AW = N > 1 ? $clog2(N) : 1;
  localparam integer N_M1 = N - 1;
  localparam [15:0] N_LAST = N_M1[15:0];
  localparam signed [15:0] GAIN16 = GAIN[15:0];
  localparam signed [15:0] M2_16 = M2[15:0];
  localparam signed [15:0] M3_16 = M3[15:0];
  localparam signed [15:0] M4_16 = M4[15:0];

  // Round-half-up constants 2^(s-1) (0 for s = 0).
  // (Builder limits: shifts <= 40, so 2^(s-1) < 2^47.)
  function automatic signed [47:0] half(input integer s);
    half = (s > 0) ? (48'sd1 <<< (s - 1)) : 48'sd0;
  endfunction

  function automatic signed [35:0] sx36(input signed [31:0] x);  // sign-extend
    sx36 = {{4{x[31]}}, x};
  endfunction

  // ---- state memory ----
  reg [63:0] mem[0:N-1];
  reg [63:0] rdata;
  reg        we;
  reg [AW-1:0] waddr;
  reg [63:0] wdata;
  reg [15:0] n;  // neuron being updated / initialised; read address
  // n is stable for a whole update, so rdata holds mem[n] from cycle 1 on;
  // a write lands one cycle after the update (cycle 11), before the next
  // read of the same address (N = 1: cycle 12 at the earliest).
  assign out_v = wdata[31:0];
  assign out_u = wdata[63:32];
  always @(posedge clk) begin
    if (we) mem[waddr] <= wdata;
    rdata <= mem[n[AW-1:0]];
  end

  // ---- control ----
  localparam [1:0] S_INIT = 2'd0, S_IDLE = 2'd1, S_RUN = 2'd2, S_OUT = 2'd3;
  reg [1:0] state;
  reg [3:0] step;
  assign in_ready = state == S_IDLE;

  // Input operand xs = sat16(rnd(x >> X_SHIFT)).
  wire signed [47:0] x_rnd = ($signed({{16{in_x[31]}}, in_x}) + half(X_SHIFT)) >>> X_SHIFT;
  // Saturation by range checks on the top bits (cheaper than comparators):
  // a signed value fits K bits iff its bits [W-1:K-1] are all equal.
  wire xs_fits = &x_rnd[47:15] | ~|x_rnd[47:15];
  wire signed [15:0] xs_in = xs_fits ? x_rnd[15:0] : (x_rnd[47] ? 16'sh8000 : 16'sh7fff);

  // Wide intermediates are truncated where the header proves the value fits.
  /* verilator lint_off UNUSEDSIGNAL */
  reg signed [15:0] xs_r;
  reg signed [31:0] v_r, U_r;
  reg signed [31:0] J_r, p1_r, sq_r, c3v_r, c2w2_r, c4u_r;
  reg signed [47:0] acc_r;

  // Operands derived from the state (header: w, wh, wl, vh, Uh, Ul).
  wire signed [31:0] w = v_r + W_OFFSET;
  wire signed [15:0] wh = w[30:15];
  wire signed [15:0] wl = {1'b0, w[14:0]};
  wire signed [32:0] vh_full = ($signed({v_r[31], v_r}) + 33'sd8192) >>> 14;
  wire signed [15:0] vh = vh_full[15:0];
  wire signed [15:0] uh = U_r[30:15];
  wire signed [15:0] ul = {1'b0, U_r[14:0]};
  wire signed [15:0] sqh = sq_r[30:15];
  wire signed [15:0] sql = {1'b0, sq_r[14:0]};

  // ---- the multiplier: one product per cycle, registered ----
  reg signed [15:0] ma, mb;
  reg signed [31:0] prod;
  always @* begin
    case (step)
      4'd0: begin ma = xs_r; mb = GAIN16; end
      4'd1: begin ma = wh; mb = wh; end
      4'd2: begin ma = wh; mb = wl; end
      4'd3: begin ma = M3_16; mb = vh; end
      4'd4: begin ma = M2_16; mb = sqh; end
      4'd5: begin ma = M2_16; mb = sql; end
      4'd6: begin ma = M4_16; mb = uh; end
      default: begin ma = M4_16; mb = ul; end
    endcase
  end
  always @(posedge clk) prod <= ma * mb;

  // Products arriving one cycle later, scaled as in the header.
  wire signed [47:0] p48 = {{16{prod[31]}}, prod};
  wire signed [47:0] j_rnd = (p48 + half(GSR)) >>> GSR;
  wire signed [47:0] j_wide = j_rnd <<< GSL;
  wire j_fits = &j_wide[47:31] | ~|j_wide[47:31];
  wire signed [31:0] j_sat = j_fits ? j_wide[31:0] : (j_wide[47] ? 32'sh80000000 : 32'sh7fffffff);
  wire signed [31:0] p2_rnd = (prod + 32'sd8192) >>> 14;
  wire signed [47:0] c3v_w = (p48 + half(S3)) >>> S3;
  wire signed [47:0] acc_sum = acc_r + p48;
  wire signed [47:0] acc_rnd2 = (acc_sum + half(S2)) >>> S2;
  wire signed [47:0] acc_rnd4 = (acc_sum + half(S4)) >>> S4;

  // ---- final update (cycle 10) ----
  wire signed [47:0] u22_w = ($signed({{16{U_r[31]}}, U_r}) + half(US)) >>> US;
  wire signed [35:0] u22 = u22_w[35:0];
  wire signed [35:0] v_new = sx36(v_r) + sx36(c2w2_r) + sx36(C_CONST) - u22 + sx36(J_r);
  wire signed [35:0] u_sum = sx36(U_r) + sx36(c3v_r) - sx36(c4u_r);
  wire u_fits = &u_sum[35:30] | ~|u_sum[35:30];  // U range: signed 31 bits
  wire signed [35:0] u_sat = u_fits ? u_sum : (u_sum[35] ? U_MIN : U_MAX);
  wire signed [35:0] u_jmp = u_sat + sx36(U_JUMP);
  wire uj_fits = &u_jmp[35:30] | ~|u_jmp[35:30];
  wire signed [35:0] u_jsat = uj_fits ? u_jmp : (u_jmp[35] ? U_MIN : U_MAX);
  /* verilator lint_on UNUSEDSIGNAL */
  wire spike = v_new >= V_PEAK;
  wire v_low = v_new[35] & ~&v_new[35:29];  // v_new < -2^29 (V_MIN)
  wire signed [31:0] v_fin = spike ? V_RESET[31:0] : v_low ? V_MIN[31:0] : v_new[31:0];
  wire signed [31:0] u_fin = spike ? u_jsat[31:0] : u_sat[31:0];

  always @(posedge clk) begin
    we <= 1'b0;
    if (rst) begin
      state <= S_INIT;
      n <= 16'd0;
      step <= 4'd0;
      out_valid <= 1'b0;
    end else begin
      case (state)
        S_INIT: begin
          we <= 1'b1;
          waddr <= n[AW-1:0];
          wdata <= {U_INIT[31:0], V_INIT[31:0]};
          if (n == N_LAST) begin
            n <= 16'd0;
            state <= S_IDLE;
          end else n <= n + 16'd1;
        end
        S_IDLE: if (in_valid) begin
          xs_r <= xs_in;
          out_t <= in_t;
          step <= 4'd0;
          state <= S_RUN;
        end
        S_RUN: begin
          step <= step + 4'd1;
          // Cycle = step + 1 after the input handshake; the product of the
          // operands chosen at step s arrives in prod at step s + 1.
          case (step)
            4'd0: begin v_r <= rdata[31:0]; U_r <= rdata[63:32]; end
            4'd1: J_r <= j_sat;
            4'd2: p1_r <= prod;
            4'd3: sq_r <= p1_r + p2_rnd;
            4'd4: c3v_r <= c3v_w[31:0];
            4'd5: acc_r <= p48 <<< 15;
            4'd6: c2w2_r <= acc_rnd2[31:0];
            4'd7: acc_r <= p48 <<< 15;
            4'd8: c4u_r <= acc_rnd4[31:0];
            default: begin  // 9 (cycle 10): write back, emit
              we <= 1'b1;
              waddr <= n[AW-1:0];
              wdata <= {u_fin, v_fin};
              out_neuron <= n;
              out_spike <= spike;
              out_last <= n == N_LAST;
              out_valid <= 1'b1;
              n <= (n == N_LAST) ? 16'd0 : n + 16'd1;
              state <= S_OUT;
            end
          endcase
        end
        default: if (out_ready) begin  // S_OUT
          out_valid <= 1'b0;
          state <= S_IDLE;
        end
      endcase
    end
  end
endmodule
