// carrier_demix: least-squares cross-talk cancellation of K carriers + DC.
// Bit-exact implementation of hls/carrier_demix.h (formats, rounding,
// saturation and the maths are stated there; cost: docs/carrier_demix.md).
//
// Per frame: K+1 input tokens {k, re, im} (k = K is the DC channel, `last`
// on it) are rotated to the oldest-sample phase reference and stored as
// b[0..2K]; then rows 0..2K-1 of y = coef * b are accumulated on the same
// single multiplier and each pair of rows is emitted as one output token
// {k, re = y[2k], im = -y[2k+1]}, `last` on k = K-1. (The DC row y[2K] is
// not streamed and not computed here.)
//
// Tables are written through the config port (host-side builder
// hls/carrier_demix_config.h), one word per handshake, only between frames:
//   cfg_sel 0: inc[addr]   1: qsin[addr]   2: coef[addr] (row-major, 2K+1)
//   cfg_sel 3: carriers K = data: clears b and restarts every phase at
//              (1 - N) inc_k (N - 1 cycles of phase -= inc), as configure().
// Timing with both ends always ready (dim = 2K+1): an input token occupies
// 8 cycles (handshake, 2 table reads, 4 products incl. store); after the
// frame's last token 1 prefetch cycle, then per output token 2 dim cycles
// (two rows) + 1 output cycle, then K phase-update cycles (one adder):
//   latency last input -> first output = 2 dim + 9   (35 for K = 6)
//   output spacing                      = 2 dim + 1   (27)
//   II per frame = 8 (K+1) + 1 + K (2 dim + 1) + K    (225 for K = 6)
// asserted by tests/rtl/carrier_demix_test.cpp; under the 342 cycles per
// sample at 12 MHz and 35 kHz.
// Area (Yosys 0.23 synth_ice40 -dsp, defaults): 1114 SB_LUT4, 558 flip-flops,
// 282 SB_CARRY, 2 SB_MAC16 (the 25x16 multiplier), 7 SB_RAM40_4K.
module carrier_demix #(
    parameter integer K_MAX = 6,
    parameter integer N = 32,
    parameter integer ACC_W = 24,
    parameter integer OUT_W = 24,
    parameter integer TW = 10,
    parameter integer SW = 16,
    parameter integer CW = 16,
    parameter integer CF = 14,
    parameter integer K_W = 8
) (
    input  wire             clk,
    input  wire             rst,
    // configuration
    input  wire             cfg_valid,
    output wire             cfg_ready,
    input  wire [1:0]       cfg_sel,
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [9:0]       cfg_addr,   // table index (bits used: as wide as the table)
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [31:0]      cfg_data,
    // sums in (sdft_bank tokens, K carriers + DC)
    input  wire             in_valid,
    output wire             in_ready,
    input  wire [K_W-1:0]   in_k,
    input  wire [ACC_W-1:0] in_re,
    input  wire [ACC_W-1:0] in_im,
    input  wire             in_last,
    // demixed amplitudes out
    output wire             out_valid,
    input  wire             out_ready,
    output wire [K_W-1:0]   out_k,
    output wire [OUT_W-1:0] out_re,
    output wire [OUT_W-1:0] out_im,
    output wire             out_last
);
  localparam integer DIM_MAX = 2 * K_MAX + 1;
  localparam integer Q = 1 << (TW - 2);
  localparam integer QN = Q + 1;
  localparam integer QAW = TW - 1;                 // table address bits
  localparam integer BW = ACC_W + 1;               // rotated sums
  localparam integer MBW = (SW > CW) ? SW : CW;    // multiplier B operand
  localparam integer PW = BW + MBW;                // product
  localparam integer AW = PW + 6;                  // accumulator (<= 33 terms)
  localparam integer NC = DIM_MAX * DIM_MAX;
  localparam integer CAW = $clog2(NC);             // coef address bits
  localparam integer BIW = $clog2(DIM_MAX);        // b index bits
  localparam integer KIW = $clog2(K_MAX > 1 ? K_MAX : 2);

  localparam [3:0] S_IN = 4'd0, S_INIT = 4'd1, S_TAB0 = 4'd2, S_TAB1 = 4'd3, S_TAB2 = 4'd4,
                   S_ROT0 = 4'd5, S_ROT1 = 4'd6, S_ROT2 = 4'd7, S_ROT3 = 4'd8,
                   S_PRE = 4'd9, S_MAT = 4'd10, S_OUT = 4'd11, S_PHASE = 4'd12;
  reg [3:0] state;

  // ---- configuration storage -------------------------------------------
  reg [31:0] inc [0:K_MAX-1];
  reg [31:0] phase [0:K_MAX-1];
  reg signed [SW-1:0] qsin [0:QN-1];
  reg signed [CW-1:0] coef [0:NC-1];
  reg [K_W-1:0] carriers;
  reg [15:0] init_cnt;
  reg [KIW-1:0] pk;  // carrier whose phase is being initialised / advanced
  // One 32-bit adder for the phases: -inc while initialising, +inc per frame.
  wire [31:0] ph_next = (state == S_INIT) ? phase[pk] - inc[pk] : phase[pk] + inc[pk];
  wire pk_last = ({{(K_W - KIW){1'b0}}, pk} == carriers - 1'b1);

  wire cfg_fire = cfg_valid && cfg_ready;
  assign cfg_ready = (state == S_IN);
  assign in_ready = (state == S_IN) && !cfg_valid;
  wire in_fire = in_valid && in_ready;

  // ---- rotation ----------------------------------------------------------
  reg [K_W-1:0] k_r;
  reg last_r;
  reg signed [ACC_W-1:0] re_r, im_r;
  reg [TW-1:0] idx_r;
  reg signed [SW-1:0] c_r, s_r;
  reg signed [SW-1:0] tab_q;
  reg tab_neg_q;
  reg signed [AW-1:0] acc;
  // b in block RAM: one write port (rotation results, cleared during
  // S_INIT), one registered read port prefetched like the coefficients.
  (* ram_style = "block" *) reg signed [BW-1:0] b [0:DIM_MAX-1];
  reg signed [BW-1:0] b_q;
  reg [BIW-1:0] b_raddr;
  reg [BIW:0] clr;
  wire is_dc = (k_r == carriers);

  // Index of the phase of the oldest sample, rounded half up to TW bits.
  wire [KIW-1:0] in_k_lim = (in_k < K_MAX[K_W-1:0]) ? in_k[KIW-1:0] : {KIW{1'b0}};
  // Only the top TW+1 phase bits matter; bit 0 of the sum is the rounding.
  /* verilator lint_off UNUSEDSIGNAL */
  wire [31:0] ph_sel = phase[in_k_lim];
  wire [TW:0] ph_top = ph_sel[31:31-TW] + {{TW{1'b0}}, 1'b1};
  /* verilator lint_on UNUSEDSIGNAL */
  wire [TW-1:0] in_idx = (in_k < carriers) ? ph_top[TW:1] : {TW{1'b0}};

  // Quarter-table lookup of sin(idx) (lk = idx) or cos(idx) (lk = idx + Q).
  wire [TW-1:0] lk = (state == S_TAB0) ? idx_r + Q[TW-1:0] : idx_r;
  wire [TW-3:0] lk_o = lk[TW-3:0];
  wire [QAW-1:0] lk_addr = lk[TW-2] ? (Q[QAW-1:0] - {1'b0, lk_o}) : {1'b0, lk_o};
  wire lk_neg = lk[TW-1];
  wire signed [SW-1:0] tab_val = tab_neg_q ? -tab_q : tab_q;

  // ---- matrix ------------------------------------------------------------
  reg [CAW-1:0] coef_addr;
  reg signed [CW-1:0] coef_q;
  reg [5:0] row, col;
  reg [K_W-1:0] dim;  // 2K+1
  reg signed [OUT_W-1:0] y_even, y_odd;

  // ---- the one multiplier ------------------------------------------------
  reg signed [BW-1:0] mul_a;
  reg signed [MBW-1:0] mul_b;
  always @(*) begin
    case (state)
      S_ROT0: begin mul_a = BW'(re_r); mul_b = MBW'(c_r); end
      S_ROT1: begin mul_a = BW'(im_r); mul_b = MBW'(s_r); end
      S_ROT2: begin mul_a = BW'(re_r); mul_b = MBW'(s_r); end
      S_ROT3: begin mul_a = BW'(im_r); mul_b = MBW'(c_r); end
      default: begin mul_a = b_q; mul_b = MBW'(coef_q); end
    endcase
  end
  wire signed [PW-1:0] prod = mul_a * mul_b;
  wire signed [AW-1:0] prod_x = AW'(prod);

  // One adder for every accumulation (subtract in S_ROT1). The rounding
  // constants are preloaded into acc, so the results are plain shifts:
  //   rotation: (re C -+ im S + 2^(SW-2)) >>> (SW-1), BW bits;
  //   matrix  : (sum_j coef b + 2^(CF-1)) >>> CF, saturated to OUT_W bits.
  localparam signed [AW-1:0] ROT_HALF = AW'(1) <<< (SW - 2);
  localparam signed [AW-1:0] MAT_HALF = AW'(1) <<< (CF - 1);
  wire sub = (state == S_ROT1);
  wire signed [AW-1:0] sum = sub ? acc - prod_x : acc + prod_x;
  wire signed [BW-1:0] rot_b = sum[BW+SW-2:SW-1];
  // y fits OUT_W bits iff sum[AW-1 : OUT_W-1+CF] are all equal.
  wire [AW-OUT_W-CF:0] y_top = sum[AW-1:OUT_W-1+CF];
  wire y_fits = (y_top == {(AW - OUT_W - CF + 1){1'b0}}) || (y_top == {(AW - OUT_W - CF + 1){1'b1}});
  wire signed [OUT_W-1:0] mat_y = y_fits ? sum[OUT_W-1+CF:CF] :
                                  sum[AW-1] ? {1'b1, {(OUT_W - 1){1'b0}}} : {1'b0, {(OUT_W - 1){1'b1}}};
  wire last_col = ({2'b00, col} == dim - 1'b1);

  // Output token.
  wire [OUT_W:0] neg_odd = -{y_odd[OUT_W-1], y_odd};
  assign out_valid = (state == S_OUT);
  assign out_k = {{(K_W - 5){1'b0}}, row[5:1]};
  assign out_re = y_even;
  assign out_im = (neg_odd[OUT_W] != neg_odd[OUT_W-1]) ? {1'b0, {(OUT_W - 1){1'b1}}} :
                  neg_odd[OUT_W-1:0];
  assign out_last = ({3'b000, row[5:1]} == carriers - 1'b1);

  // The b write port: Re P in S_ROT1 (index 2k; DC: 2K), -Im P in S_ROT3
  // (2k+1, carriers only), zeros for the first 2K+1 entries in S_INIT.
  wire b_we = (state == S_ROT1) || (state == S_ROT3 && !is_dc) ||
              (state == S_INIT && {{(K_W - BIW - 1){1'b0}}, clr} < dim);
  wire [BIW-1:0] b_waddr = (state == S_INIT) ? clr[BIW-1:0] :
                           {k_r[BIW-2:0], (state == S_ROT3)};
  wire signed [BW-1:0] b_wdata = (state == S_INIT) ? {BW{1'b0}} :
                                 (state == S_ROT3) ? -rot_b : rot_b;
  wire [BIW-1:0] b_raddr_next = ({{(K_W - BIW){1'b0}}, b_raddr} == dim - 1'b1) ?
                                {BIW{1'b0}} : b_raddr + 1'b1;
  always @(posedge clk) begin
    if (b_we) b[b_waddr] <= b_wdata;
    if (state == S_INIT) clr <= clr + 1'b1;
  end

  integer i;
  always @(posedge clk) begin
    if (rst) begin
      state <= S_IN;
      carriers <= {K_W{1'b0}};
    end else begin
      case (state)
        S_IN:
          if (cfg_fire) begin
            case (cfg_sel)
              2'd0: inc[cfg_addr[KIW-1:0]] <= cfg_data;
              2'd1: qsin[cfg_addr[QAW-1:0]] <= cfg_data[SW-1:0];
              2'd2: coef[cfg_addr[CAW-1:0]] <= cfg_data[CW-1:0];
              default: begin
                carriers <= cfg_data[K_W-1:0];
                dim <= {cfg_data[K_W-2:0], 1'b1};
                for (i = 0; i < K_MAX; i = i + 1) phase[i] <= 32'd0;
                clr <= {(BIW + 1){1'b0}};
                init_cnt <= 16'd0;
                pk <= {KIW{1'b0}};
                state <= (cfg_data[K_W-1:0] == {K_W{1'b0}}) ? S_IN : S_INIT;
              end
            endcase
          end else if (in_fire) begin
            k_r <= in_k;
            last_r <= in_last;
            re_r <= in_re;
            im_r <= in_im;
            idx_r <= in_idx;
            if (carriers == {K_W{1'b0}} || in_k > carriers) state <= S_IN;  // dropped
            else state <= S_TAB0;
          end
        S_INIT: begin  // phase_k = (1 - N) inc_k: N - 1 subtractions per carrier
          if (init_cnt == 16'(N - 1)) begin
            init_cnt <= 16'd0;
            pk <= pk + 1'b1;
            if (pk_last) state <= S_IN;
          end else begin
            phase[pk] <= ph_next;
            init_cnt <= init_cnt + 16'd1;
          end
        end
        S_TAB0: begin  // table read: cos
          tab_q <= qsin[lk_addr];
          tab_neg_q <= lk_neg;
          state <= S_TAB1;
        end
        S_TAB1: begin  // table read: sin; cos ready
          c_r <= tab_val;
          tab_q <= qsin[lk_addr];
          tab_neg_q <= lk_neg;
          state <= S_TAB2;
        end
        S_TAB2: begin
          s_r <= tab_val;
          acc <= ROT_HALF;
          state <= S_ROT0;
        end
        S_ROT0: begin  // re C
          acc <= sum;
          state <= S_ROT1;
        end
        S_ROT1: begin  // - im S -> Re P = sum x cos(w i) (DC: sum x)
          acc <= ROT_HALF;
          state <= S_ROT2;
        end
        S_ROT2: begin  // re S
          acc <= sum;
          state <= S_ROT3;
        end
        S_ROT3: begin  // + im C -> Im P; b = -Im P = sum x sin(w i)
          acc <= MAT_HALF;
          if (last_r) begin
            coef_addr <= {CAW{1'b0}};
            b_raddr <= {BIW{1'b0}};
            row <= 6'd0;
            col <= 6'd0;
            state <= S_PRE;
          end else begin
            state <= S_IN;
          end
        end
        S_PRE: begin
          coef_q <= coef[coef_addr];
          coef_addr <= coef_addr + 1'b1;
          b_q <= b[b_raddr];
          b_raddr <= b_raddr_next;
          state <= S_MAT;
        end
        S_MAT: begin
          coef_q <= coef[coef_addr];
          coef_addr <= coef_addr + 1'b1;
          b_q <= b[b_raddr];
          b_raddr <= b_raddr_next;
          if (last_col) begin
            acc <= MAT_HALF;
            col <= 6'd0;
            if (row[0]) begin
              y_odd <= mat_y;
              state <= S_OUT;
            end else begin
              y_even <= mat_y;
              row <= row + 6'd1;
            end
          end else begin
            acc <= sum;
            col <= col + 6'd1;
          end
        end
        S_OUT:
          if (out_ready) begin
            if ({3'b000, row[5:1]} == carriers - 1'b1) begin
              pk <= {KIW{1'b0}};
              state <= S_PHASE;
            end else begin
              row <= row + 6'd1;
              state <= S_MAT;
            end
          end
        S_PHASE: begin  // one carrier per cycle
          phase[pk] <= ph_next;
          pk <= pk + 1'b1;
          if (pk_last) state <= S_IN;
        end
        default: state <= S_IN;
      endcase
    end
  end
endmodule
