// taxel_reconstruct: one frame of carrier magnitudes {k, mag} (rows first,
// then columns; k == rows+cols-1 closes the frame) -> taxel tokens
// {row, col, value, last} for active rows x active columns, row-major.
// Bit-exact implementation of hls/taxel_reconstruct.h (modes, formats,
// rounding and saturation are stated there):
//   mode 0 Product     value = sat(round(m_i*m_j >> shift))
//   mode 1 Conductance g = sat16(round(isqrt(m_i*m_j)*recip >> recip_shift))
//   mode 2 Pressure    PWL(g) through the 16-entry table (tab_* write port).
// One 16x16 multiplier shared by m_i*m_j, root*recip, (g-g_s)*slope (one
// SB_MAC16 with `synth_ice40 -dsp`) and one rounding shifter.
// States (cycles per taxel c: Product 1, Conductance MAG_W+2, Pressure MAG_W+7):
//   IN     in_ready = 1; stores mag and its activity bit (mag >= threshold).
//   START  1 cycle: first active (row, col); none -> IN (idle frame).
//   SQRT   MAG_W cycles, one root bit each.   GSCALE 1: g = root*recip.
//   SEARCH 4 cycles, binary search of g_tab.  INTERP 1: value from the table.
//   OUT    out_valid = 1; on the handshake the next taxel's product is formed
//          in the same cycle (Product: straight into the output register).
// Frame period with out_ready = 1: K + 1 + T*c cycles, T active taxels.
module taxel_reconstruct #(
    parameter integer R_MAX = 16,
    parameter integer C_MAX = 16,
    parameter integer MAG_W = 16,   // <= 16
    parameter integer TAX_W = 16,   // <= 32
    parameter integer K_W = 8       // width of k, row, col
) (
    input  wire             clk,
    input  wire             rst,              // synchronous, active high
    // configuration: hold steady while a frame is in flight
    input  wire [K_W-1:0]   cfg_rows,         // 1..R_MAX
    input  wire [K_W-1:0]   cfg_cols,         // 1..C_MAX
    input  wire [1:0]       cfg_mode,
    input  wire [4:0]       cfg_shift,
    input  wire [MAG_W-1:0] cfg_threshold,
    input  wire [15:0]      cfg_recip,
    input  wire [4:0]       cfg_recip_shift,
    input  wire [4:0]       cfg_slope_shift,
    input  wire             tab_we,           // PWL table write port
    input  wire [3:0]       tab_addr,
    input  wire [15:0]      tab_g,
    input  wire [TAX_W-1:0] tab_p,
    input  wire [15:0]      tab_slope,
    // magnitude stream in
    input  wire             in_valid,
    output wire             in_ready,
    input  wire [K_W-1:0]   in_k,
    input  wire [MAG_W-1:0] in_mag,
    // taxel stream out
    output wire             out_valid,
    input  wire             out_ready,
    output reg  [K_W-1:0]   out_row,
    output reg  [K_W-1:0]   out_col,
    output reg  [TAX_W-1:0] out_value,
    output wire             out_last
);
  localparam [2:0] S_IN = 3'd0, S_START = 3'd1, S_SQRT = 3'd2, S_GSCALE = 3'd3,
                   S_SEARCH = 3'd4, S_INTERP = 3'd5, S_OUT = 3'd6;
  localparam [1:0] M_PRODUCT = 2'd0, M_COND = 2'd1;
  localparam [33:0] TAX_MAX = (34'd1 << TAX_W) - 34'd1;
  localparam integer RI_W = (R_MAX > 1) ? $clog2(R_MAX) : 1;  // array index widths
  localparam integer CI_W = (C_MAX > 1) ? $clog2(C_MAX) : 1;
  localparam integer SQ_LAST_I = MAG_W - 1;
  localparam [4:0] SQ_LAST = SQ_LAST_I[4:0];

  reg [2:0] state;
  reg [MAG_W-1:0] row_mag [0:R_MAX-1];
  reg [MAG_W-1:0] col_mag [0:C_MAX-1];
  reg [R_MAX-1:0] row_act;
  reg [C_MAX-1:0] col_act;

  // ---- input side ---------------------------------------------------------
  wire in_fire = in_valid && in_ready;
  assign in_ready = (state == S_IN);
  wire [K_W-1:0] k_col = in_k - cfg_rows;
  wire is_row = in_k < cfg_rows;
  wire is_col = !is_row && (k_col < cfg_cols);
  wire frame_end = (in_k == cfg_rows + cfg_cols - 1'b1);
  wire in_active = in_mag >= cfg_threshold;

  // ---- next active (row, col) ---------------------------------------------
  // row_left: active rows not started yet; col_left: active columns still to
  // come in row ri. x & (x - 1) clears the lowest set bit (the one taken).
  reg [K_W-1:0] ri, cj;            // taxel being computed / offered
  reg [R_MAX-1:0] row_left;
  reg [C_MAX-1:0] col_left;
  reg [K_W-1:0] lo_row_act, lo_col_act, lo_row_left, lo_col_left;  // lowest set bit
  integer i;
  always @* begin
    lo_row_act = {K_W{1'b0}}; lo_row_left = {K_W{1'b0}};
    for (i = R_MAX - 1; i >= 0; i = i - 1) begin
      if (row_act[i]) lo_row_act = i[K_W-1:0];
      if (row_left[i]) lo_row_left = i[K_W-1:0];
    end
    lo_col_act = {K_W{1'b0}}; lo_col_left = {K_W{1'b0}};
    for (i = C_MAX - 1; i >= 0; i = i - 1) begin
      if (col_act[i]) lo_col_act = i[K_W-1:0];
      if (col_left[i]) lo_col_left = i[K_W-1:0];
    end
  end
  wire same_row = (state != S_START) && (|col_left);  // next taxel stays in row ri
  wire has_next = |col_left || |row_left;
  assign out_last = !has_next;
  // Taxel whose product is formed this cycle (START: first; OUT: next).
  wire [K_W-1:0] sel_r = (state == S_START) ? lo_row_act : (same_row ? ri : lo_row_left);
  wire [K_W-1:0] sel_c = same_row ? lo_col_left : lo_col_act;
  wire [R_MAX-1:0] rows_src = (state == S_START) ? row_act : row_left;
  wire [C_MAX-1:0] cols_src = same_row ? col_left : col_act;

  // ---- PWL table: three 16-entry memories, synchronous read ---------------
  reg [15:0] g_mem [0:15];
  reg [TAX_W-1:0] p_mem [0:15];
  reg [15:0] s_mem [0:15];
  reg [15:0] g_rd, s_rd;
  reg [TAX_W-1:0] p_rd;
  reg [3:0] seg, g_raddr;
  reg [1:0] step;
  reg [15:0] g, g_seg;             // g of the taxel, g_tab[seg]
  wire [3:0] bit_now = 4'd8 >> step;
  wire take = (g_rd <= g);
  wire [3:0] seg_new = take ? (seg | bit_now) : seg;
  always @* g_raddr = (state == S_SEARCH) ? (seg_new | (bit_now >> 1)) : 4'd8;
  always @(posedge clk) begin
    if (tab_we) begin
      g_mem[tab_addr] <= tab_g;
      p_mem[tab_addr] <= tab_p;
      s_mem[tab_addr] <= tab_slope;
    end
    g_rd <= g_mem[g_raddr];
    p_rd <= p_mem[seg_new];
    s_rd <= s_mem[seg_new];
  end

  // ---- square root state (hls/isqrt.h: one step per cycle) ----------------
  reg [2*MAG_W-1:0] rad;
  reg [MAG_W-1:0] root;
  reg [MAG_W+1:0] rem;
  reg [4:0] cnt;
  wire [MAG_W+3:0] sq_r = {rem, rad[2*MAG_W-1:2*MAG_W-2]};
  wire [MAG_W+3:0] sq_trial = {2'b00, root, 2'b01};
  wire sq_ge = sq_r >= sq_trial;
  wire [MAG_W+3:0] sq_diff = sq_r - sq_trial;  // < 2^(MAG_W+2) when sq_ge
  wire unused_sq = &{1'b0, sq_diff[MAG_W+3:MAG_W+2]};

  // ---- the one multiplier and the one rounding shifter --------------------
  reg [15:0] mul_a, mul_b;
  always @* begin
    mul_a = 16'd0; mul_b = 16'd0;
    case (state)
      S_GSCALE: begin mul_a[MAG_W-1:0] = root; mul_b = cfg_recip; end
      S_INTERP: begin mul_a = g - g_seg; mul_b = s_rd; end
      default:  begin mul_a[MAG_W-1:0] = row_mag[sel_r[RI_W-1:0]]; mul_b[MAG_W-1:0] = col_mag[sel_c[CI_W-1:0]]; end
    endcase
  end
  wire [31:0] mul_p = mul_a * mul_b;
  // Shift amount of the state to come, registered (GSCALE follows SQRT,
  // INTERP follows SEARCH): keeps the state decode off the datapath.
  reg [4:0] sh;
  always @(posedge clk)
    sh <= (state == S_SQRT) ? cfg_recip_shift : (state == S_SEARCH) ? cfg_slope_shift : cfg_shift;
  // Round half up as ((2x >> sh) + 1) >> 1, equal to (x + 2^(sh-1)) >> sh
  // (and to x for sh = 0): shift first, then one short increment.
  wire [33:0] sh2 = {1'b0, mul_p, 1'b0} >> sh;
  wire [32:0] rounded = sh2[33:1] + {32'd0, sh2[0]};
  wire [33:0] interp = {1'b0, rounded} + {{(34 - TAX_W){1'b0}}, p_rd};
  wire [TAX_W-1:0] prod_sat = ({1'b0, rounded} > TAX_MAX) ? TAX_MAX[TAX_W-1:0]
                                                          : rounded[TAX_W-1:0];
  wire [15:0] g_sat = (rounded > 33'hFFFF) ? 16'hFFFF : rounded[15:0];
  wire [TAX_W-1:0] g_out = ({18'd0, g_sat} > TAX_MAX) ? TAX_MAX[TAX_W-1:0]
                                                      : g_sat[TAX_W-1:0];
  wire [TAX_W-1:0] interp_sat = (interp > TAX_MAX) ? TAX_MAX[TAX_W-1:0] : interp[TAX_W-1:0];

  // Form the product of taxel (sel_r, sel_c): Product mode -> output
  // register, else start its square root.
  task automatic begin_taxel;
    begin
      ri <= sel_r;
      cj <= sel_c;
      if (!same_row) row_left <= rows_src & (rows_src - 1'b1);
      col_left <= cols_src & (cols_src - 1'b1);
      if (cfg_mode == M_PRODUCT) begin
        out_value <= prod_sat;
        state <= S_OUT;
      end else begin
        rad <= mul_p[2*MAG_W-1:0];
        root <= {MAG_W{1'b0}};
        rem <= {(MAG_W+2){1'b0}};
        cnt <= 5'd0;
        state <= S_SQRT;
      end
    end
  endtask

  // Masks are rewritten only below cfg_rows/cfg_cols: clear them per frame.
  task automatic end_frame;
    begin
      row_act <= {R_MAX{1'b0}};
      col_act <= {C_MAX{1'b0}};
      state <= S_IN;
    end
  endtask

  assign out_valid = (state == S_OUT);
  always @* begin
    out_row = ri;
    out_col = cj;
  end

  always @(posedge clk) begin
    if (rst) begin
      state <= S_IN;
      row_act <= {R_MAX{1'b0}};
      col_act <= {C_MAX{1'b0}};
      row_left <= {R_MAX{1'b0}};
      col_left <= {C_MAX{1'b0}};
      ri <= {K_W{1'b0}};
      cj <= {K_W{1'b0}};
    end else begin
      case (state)
        S_IN: if (in_fire) begin
          if (is_row) begin
            row_mag[in_k[RI_W-1:0]] <= in_mag;
            row_act[in_k[RI_W-1:0]] <= in_active;
          end else if (is_col) begin
            col_mag[k_col[CI_W-1:0]] <= in_mag;
            col_act[k_col[CI_W-1:0]] <= in_active;
          end
          if (frame_end) state <= S_START;
        end
        S_START:
          if (|row_act && |col_act) begin_taxel();
          else end_frame();
        S_SQRT: begin
          rad <= rad << 2;
          root <= {root[MAG_W-2:0], sq_ge};
          rem <= sq_ge ? sq_diff[MAG_W+1:0] : sq_r[MAG_W+1:0];
          cnt <= cnt + 5'd1;
          if (cnt == SQ_LAST) state <= S_GSCALE;
        end
        S_GSCALE: begin
          g <= g_sat;
          seg <= 4'd0;
          g_seg <= 16'd0;
          step <= 2'd0;
          if (cfg_mode == M_COND) begin
            out_value <= g_out;
            state <= S_OUT;
          end else state <= S_SEARCH;
        end
        S_SEARCH: begin
          seg <= seg_new;
          if (take) g_seg <= g_rd;
          step <= step + 2'd1;
          if (step == 2'd3) state <= S_INTERP;
        end
        S_INTERP: begin
          out_value <= interp_sat;
          state <= S_OUT;
        end
        S_OUT: if (out_ready) begin
          if (has_next) begin_taxel();
          else end_frame();
        end
        default: state <= S_IN;
      endcase
    end
  end
endmodule
