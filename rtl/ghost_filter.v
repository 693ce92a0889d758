// ghost_filter: multi-touch active-site tracking (thesis §5.2) on a stream of
// carrier magnitude frames {k, mag} (rows first, k == rows+cols-1 closes the
// frame) -> the active sites of each frame as {row, col, value, last}.
// Bit-exact implementation of hls/ghost_filter.h (algorithm, formats,
// rounding there). One 16x16 multiplier (one SB_MAC16 with -dsp) serves the
// release test m_i*m_j < release2, the site value and root*recip.
// History: a ring of lookback x K magnitudes in one memory (EBR), address
// {slot, k}; cleared after reset (CLEAR: L_MAX * 2^KB cycles, in_ready low).
// A config change (sizes, lookback) needs a reset, as the HLS configure().
// States and cycles per frame with out_ready = 1 (P = max(rows, cols)):
//   IN       K   one token per cycle; the history read of token k returns
//                the next cycle, when its rise, rem and the running row /
//                column argmax are updated (a 1-token pipeline).
//   FLUSH    1   the last token's rise; head advances.
//   DECIDE   1   per decision: improved mode and both maxima > pair_tol ->
//                subtract the smaller, mark the pair pending, RESCAN (P
//                cycles: rows and columns in parallel) and DECIDE again;
//                else commit: the thesis site, or (pairing fits) COMMIT
//   COMMIT   steps   one pending pair per cycle into the site matrix.
//   REL0/REL 1 + S_b   one site per cycle: drop it if m_i*m_j < release2.
//   EMIT0    1   first surviving site's product (none -> IN).
//   SQRT/GSCALE/OUT    c = 1 (product) or MAG_W + 2 (conductance) per site.
// Frame period = K + 4 + steps*(P+1) + (fits ? steps : 0) + S_b + S_a*c.
module ghost_filter #(
    parameter integer R_MAX = 16,
    parameter integer C_MAX = 16,
    parameter integer L_MAX = 32,   // max lookback (frames)
    parameter integer MAG_W = 16,   // <= 16
    parameter integer TAX_W = 16,   // <= 32
    parameter integer K_W = 8
) (
    input  wire               clk,
    input  wire               rst,          // synchronous, active high
    input  wire [K_W-1:0]     cfg_rows,
    input  wire [K_W-1:0]     cfg_cols,
    input  wire [15:0]        cfg_lookback, // 1..L_MAX
    input  wire               cfg_improved,
    input  wire [MAG_W-1:0]   cfg_onset,
    input  wire [MAG_W-1:0]   cfg_pair_tol,
    input  wire [2*MAG_W-1:0] cfg_release2,
    input  wire               cfg_conductance,
    input  wire [4:0]         cfg_shift,
    input  wire [15:0]        cfg_recip,
    input  wire [4:0]         cfg_recip_shift,
    input  wire               in_valid,
    output wire               in_ready,
    input  wire [K_W-1:0]     in_k,
    input  wire [MAG_W-1:0]   in_mag,
    output wire               out_valid,
    input  wire               out_ready,
    output reg  [K_W-1:0]     out_row,
    output reg  [K_W-1:0]     out_col,
    output reg  [TAX_W-1:0]   out_value,
    output wire               out_last
);
  localparam integer K_MAX = R_MAX + C_MAX;
  localparam integer KB = $clog2(K_MAX);
  localparam integer LB = (L_MAX > 1) ? $clog2(L_MAX) : 1;
  localparam integer RI_W = (R_MAX > 1) ? $clog2(R_MAX) : 1;
  localparam integer CI_W = (C_MAX > 1) ? $clog2(C_MAX) : 1;
  localparam integer IX_W = (RI_W > CI_W) ? RI_W : CI_W;
  localparam integer DEPTH = L_MAX << KB;
  localparam [33:0] TAX_MAX = (34'd1 << TAX_W) - 34'd1;
  localparam integer SQ_LAST_I = MAG_W - 1;
  localparam [4:0] SQ_LAST = SQ_LAST_I[4:0];
  localparam integer CLR_LAST_I = DEPTH - 1;
  localparam [LB+KB-1:0] CLR_LAST = CLR_LAST_I[LB+KB-1:0];
  localparam [3:0] S_CLEAR = 4'd0, S_IN = 4'd1, S_FLUSH = 4'd2, S_DECIDE = 4'd3,
                   S_SCAN = 4'd4, S_REL0 = 4'd5, S_REL = 4'd6, S_EMIT0 = 4'd7,
                   S_SQRT = 4'd8, S_GSCALE = 4'd9, S_OUT = 4'd10,
                   S_COMMIT = 4'd11;
  reg [3:0] state;

  // ---- per-line state -----------------------------------------------------
  reg [MAG_W-1:0] row_mag [0:R_MAX-1];
  reg [MAG_W-1:0] col_mag [0:C_MAX-1];
  reg [C_MAX-1:0] site [0:R_MAX-1];     // active sites, one row mask each

  // ---- input and history ring (1-token pipeline) --------------------------
  reg [MAG_W-1:0] hist [0:DEPTH-1];
  reg [MAG_W-1:0] hist_rd;
  reg [LB-1:0] head;
  reg [LB+KB-1:0] clr_addr;
  reg p_valid, p_row;
  reg [IX_W-1:0] p_idx;                 // row index or column index
  reg [KB-1:0] p_k;
  reg [MAG_W-1:0] p_mag;
  wire in_fire = in_valid && in_ready;
  assign in_ready = (state == S_IN);
  wire in_is_row = in_k < cfg_rows;
  wire [K_W-1:0] in_col = in_k - cfg_rows;
  wire in_ok = in_is_row || (in_col < cfg_cols);
  wire frame_end = (in_k == cfg_rows + cfg_cols - 1'b1);
  wire [MAG_W:0] rise = {1'b0, p_mag} - {1'b0, hist_rd};   // two's complement
  wire rise_pos = !rise[MAG_W] && (rise[MAG_W-1:0] > cfg_onset);
  wire [MAG_W-1:0] rem_new = rise_pos ? rise[MAG_W-1:0] : {MAG_W{1'b0}};
  always @(posedge clk) begin
    if (state == S_CLEAR) hist[clr_addr] <= {MAG_W{1'b0}};
    else if (p_valid) hist[{head, p_k}] <= p_mag;
    hist_rd <= hist[{head, in_k[KB-1:0]}];
  end

  // ---- argmax: running (input) and rescans --------------------------------
  // One running argmax per side (first index of the largest rem), fed by the
  // input's rise stage and by rescans through one shared comparator each.
  reg [RI_W-1:0] am_r, th_r;
  reg [CI_W-1:0] am_c, th_c;
  reg [K_W-1:0] scan_i;
  reg [MAG_W-1:0] am_rv, am_cv;
  reg first, th_ok;                     // first DECIDE of the frame; thesis site
  wire [MAG_W-1:0] scan_rv, scan_cv;     // rem[scan_i] (memories below)
  wire [K_W-1:0] scan_last = (cfg_rows > cfg_cols) ? cfg_rows - 1'b1 : cfg_cols - 1'b1;
  wire scanning = (state == S_SCAN);
  wire [MAG_W-1:0] cand_rv = scanning ? scan_rv : rem_new;
  wire [MAG_W-1:0] cand_cv = scanning ? scan_cv : rem_new;
  wire [IX_W-1:0] cand_i = scanning ? scan_i[IX_W-1:0] : p_idx;
  wire cand_r_en = scanning ? (scan_i < cfg_rows) : (p_valid && p_row);
  wire cand_c_en = scanning ? (scan_i < cfg_cols) : (p_valid && !p_row);
  wire rv_gt = am_rv > cfg_pair_tol;
  wire cv_gt = am_cv > cfg_pair_tol;
  // thesis site: the input's argmax (saved at the first DECIDE)
  wire [RI_W-1:0] thesis_r = first ? am_r : th_r;
  wire [CI_W-1:0] thesis_c = first ? am_c : th_c;
  wire thesis_ok = first ? (am_rv != 0 && am_cv != 0) : th_ok;
  wire [MAG_W-1:0] flow = (am_rv < am_cv) ? am_rv : am_cv;
  wire pair_step = (state == S_DECIDE) && cfg_improved && rv_gt && cv_gt;

  // rem per line in two memories (EBR when large): one write port (the
  // input's rise stage, or a pairing step's subtraction), one read port
  // feeding the rescan a cycle ahead (address scan_i + 1; 0 during DECIDE).
  // The rescan's first read was issued while DECIDE wrote: if DECIDE wrote
  // index 0, the written value is taken instead (byp_*).
  reg [MAG_W-1:0] row_rem [0:R_MAX-1];
  reg [MAG_W-1:0] col_rem [0:C_MAX-1];
  reg [MAG_W-1:0] row_rem_rd, col_rem_rd, byp_rv, byp_cv;
  reg byp_r, byp_c;
  wire rr_we = pair_step || (p_valid && p_row);
  wire cr_we = pair_step || (p_valid && !p_row);
  wire [RI_W-1:0] rr_wa = pair_step ? am_r : p_idx[RI_W-1:0];
  wire [CI_W-1:0] cr_wa = pair_step ? am_c : p_idx[CI_W-1:0];
  wire [MAG_W-1:0] rr_wd = pair_step ? am_rv - flow : rem_new;
  wire [MAG_W-1:0] cr_wd = pair_step ? am_cv - flow : rem_new;
  wire [IX_W-1:0] scan_next = scanning ? scan_i[IX_W-1:0] + 1'b1 : {IX_W{1'b0}};
  always @(posedge clk) begin
    if (rr_we) row_rem[rr_wa] <= rr_wd;
    if (cr_we) col_rem[cr_wa] <= cr_wd;
    row_rem_rd <= row_rem[scan_next[RI_W-1:0]];
    col_rem_rd <= col_rem[scan_next[CI_W-1:0]];
    if (pair_step) begin
      byp_r <= (am_r == 0); byp_rv <= rr_wd;
      byp_c <= (am_c == 0); byp_cv <= cr_wd;
    end
  end
  assign scan_rv = (scan_i == 0 && byp_r) ? byp_rv : row_rem_rd;

  // Candidate pairs of this frame as a list (steps <= rising lines - 1 <
  // R_MAX + C_MAX): appended by each pairing step, read back one per cycle
  // (address one ahead) by COMMIT when the pairing fits.
  localparam integer PL = R_MAX + C_MAX;
  localparam integer PB = $clog2(PL);
  reg [RI_W+CI_W-1:0] pl [0:PL-1];
  reg [RI_W+CI_W-1:0] pl_rd;
  reg [PB-1:0] n_pend, commit_i;
  wire [PB-1:0] pl_ra = (state == S_COMMIT) ? commit_i + 1'b1 : {PB{1'b0}};
  always @(posedge clk) begin
    if (pair_step) pl[n_pend] <= {am_r, am_c};
    pl_rd <= pl[pl_ra];
  end
  wire fits = cfg_improved && !rv_gt && !cv_gt;   // the pairing explains all rises
  assign scan_cv = (scan_i == 0 && byp_c) ? byp_cv : col_rem_rd;

  // ---- site walk (release pass and emit pass) -----------------------------
  reg [K_W-1:0] ri, cj;
  reg [R_MAX-1:0] row_left, nonempty;
  reg [C_MAX-1:0] col_left;
  reg [K_W-1:0] lo_row;
  reg [C_MAX-1:0] lo_row_mask;
  reg [K_W-1:0] lo_col;
  integer i;
  always @* begin
    for (i = 0; i < R_MAX; i = i + 1) nonempty[i] = |site[i];
  end
  wire [R_MAX-1:0] rows_src = (state == S_EMIT0) ? nonempty : row_left;
  wire same_row = (state != S_EMIT0) && (|col_left);
  always @* begin
    lo_row = {K_W{1'b0}};
    for (i = R_MAX - 1; i >= 0; i = i - 1) if (rows_src[i]) lo_row = i[K_W-1:0];
  end
  always @* lo_row_mask = site[lo_row[RI_W-1:0]];
  wire [C_MAX-1:0] cols_src = same_row ? col_left : lo_row_mask;
  always @* begin
    lo_col = {K_W{1'b0}};
    for (i = C_MAX - 1; i >= 0; i = i - 1) if (cols_src[i]) lo_col = i[K_W-1:0];
  end
  wire [K_W-1:0] sel_r = same_row ? ri : lo_row;
  wire [K_W-1:0] sel_c = lo_col;
  wire [R_MAX-1:0] row_left_next = same_row ? row_left : (rows_src & (rows_src - 1'b1));
  wire [C_MAX-1:0] col_left_next = cols_src & (cols_src - 1'b1);
  wire has_next = (|row_left_next) || (|col_left_next);
  assign out_last = !((|row_left) || (|col_left));

  // ---- square root, the multiplier, rounding ------------------------------
  reg [2*MAG_W-1:0] rad;
  reg [MAG_W-1:0] root;
  reg [MAG_W+1:0] rem;
  reg [4:0] cnt;
  wire [MAG_W+3:0] sq_r = {rem, rad[2*MAG_W-1:2*MAG_W-2]};
  wire [MAG_W+3:0] sq_trial = {2'b00, root, 2'b01};
  wire sq_ge = sq_r >= sq_trial;
  wire [MAG_W+3:0] sq_diff = sq_r - sq_trial;   // < 2^(MAG_W+2) when sq_ge
  reg [15:0] mul_a, mul_b;
  always @* begin
    mul_a = 16'd0; mul_b = 16'd0;
    if (state == S_GSCALE) begin
      mul_a[MAG_W-1:0] = root; mul_b = cfg_recip;
    end else begin
      mul_a[MAG_W-1:0] = row_mag[sel_r[RI_W-1:0]];
      mul_b[MAG_W-1:0] = col_mag[sel_c[CI_W-1:0]];
    end
  end
  wire [31:0] mul_p = mul_a * mul_b;
  // Shift amount registered (GSCALE always follows SQRT); round half up as
  // ((2x >> sh) + 1) >> 1 = (x + 2^(sh-1)) >> sh (x for sh = 0).
  reg [4:0] sh;
  always @(posedge clk) sh <= (state == S_SQRT) ? cfg_recip_shift : cfg_shift;
  wire [33:0] sh2 = {1'b0, mul_p, 1'b0} >> sh;
  wire [32:0] rounded = sh2[33:1] + {32'd0, sh2[0]};
  wire [TAX_W-1:0] prod_sat = ({1'b0, rounded} > TAX_MAX) ? TAX_MAX[TAX_W-1:0]
                                                          : rounded[TAX_W-1:0];
  wire [15:0] g_sat = (rounded > 33'hFFFF) ? 16'hFFFF : rounded[15:0];
  wire [TAX_W-1:0] g_out = ({18'd0, g_sat} > TAX_MAX) ? TAX_MAX[TAX_W-1:0]
                                                      : g_sat[TAX_W-1:0];
  wire keep = {{(32 - 2 * MAG_W){1'b0}}, cfg_release2} <= mul_p;
  wire unused = &{1'b0, sq_diff[MAG_W+3:MAG_W+2], cfg_lookback};

  assign out_valid = (state == S_OUT);
  always @* begin
    out_row = ri;
    out_col = cj;
  end

  // Step the walk to site (sel_r, sel_c).
  task automatic walk;
    begin
      ri <= sel_r;
      cj <= sel_c;
      row_left <= row_left_next;
      col_left <= col_left_next;
    end
  endtask
  // Emit-pass: form the value of site (sel_r, sel_c).
  task automatic begin_site;
    begin
      walk();
      if (!cfg_conductance) begin
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
  task automatic end_frame;
    begin
      am_rv <= {MAG_W{1'b0}}; am_r <= {RI_W{1'b0}};
      am_cv <= {MAG_W{1'b0}}; am_c <= {CI_W{1'b0}};
      state <= S_IN;
    end
  endtask

  always @(posedge clk) begin
    if (rst) begin
      state <= S_CLEAR;
      clr_addr <= {(LB+KB){1'b0}};
      head <= {LB{1'b0}};
      p_valid <= 1'b0;
      row_left <= {R_MAX{1'b0}};
      col_left <= {C_MAX{1'b0}};
      ri <= {K_W{1'b0}};
      cj <= {K_W{1'b0}};
      am_rv <= {MAG_W{1'b0}}; am_r <= {RI_W{1'b0}};
      am_cv <= {MAG_W{1'b0}}; am_c <= {CI_W{1'b0}};
      for (i = 0; i < R_MAX; i = i + 1) site[i] <= {C_MAX{1'b0}};
      n_pend <= {PB{1'b0}};
    end else begin
      // rise stage of the input pipeline (token accepted last cycle)
      p_valid <= in_fire && in_ok;
      if (in_fire) begin
        p_row <= in_is_row;
        p_idx <= in_is_row ? in_k[IX_W-1:0] : in_col[IX_W-1:0];
        p_k <= in_k[KB-1:0];
        p_mag <= in_mag;
        if (in_is_row) row_mag[in_k[RI_W-1:0]] <= in_mag;
        else if (in_ok) col_mag[in_col[CI_W-1:0]] <= in_mag;
      end
      if (cand_r_en && cand_rv > am_rv) begin am_rv <= cand_rv; am_r <= cand_i[RI_W-1:0]; end
      if (cand_c_en && cand_cv > am_cv) begin am_cv <= cand_cv; am_c <= cand_i[CI_W-1:0]; end
      case (state)
        S_CLEAR: begin
          clr_addr <= clr_addr + 1'b1;
          if (clr_addr == CLR_LAST) state <= S_IN;
        end
        S_IN: if (in_fire && frame_end) state <= S_FLUSH;
        S_FLUSH: begin
          head <= (head == cfg_lookback[LB-1:0] - 1'b1) ? {LB{1'b0}} : head + 1'b1;
          first <= 1'b1;  // am_* get the last token this cycle
          state <= S_DECIDE;
        end
        S_DECIDE:
          if (pair_step) begin
            n_pend <= n_pend + 1'b1;
            first <= 1'b0;
            th_r <= thesis_r; th_c <= thesis_c; th_ok <= thesis_ok;
            am_rv <= {MAG_W{1'b0}}; am_r <= {RI_W{1'b0}};
            am_cv <= {MAG_W{1'b0}}; am_c <= {CI_W{1'b0}};
            scan_i <= {K_W{1'b0}};
            state <= S_SCAN;
          end else if (fits && n_pend != 0) begin
            commit_i <= {PB{1'b0}};
            state <= S_COMMIT;
          end else begin
            if (!fits && thesis_ok) site[thesis_r][thesis_c] <= 1'b1;
            n_pend <= {PB{1'b0}};
            state <= S_REL0;
          end
        S_COMMIT: begin
          site[pl_rd[RI_W+CI_W-1:CI_W]][pl_rd[CI_W-1:0]] <= 1'b1;
          commit_i <= commit_i + 1'b1;
          if (commit_i == n_pend - 1'b1) begin
            n_pend <= {PB{1'b0}};
            state <= S_REL0;
          end
        end
        S_SCAN: begin
          scan_i <= scan_i + 1'b1;
          if (scan_i == scan_last) state <= S_DECIDE;
        end
        S_REL0: begin
          row_left <= nonempty;
          col_left <= {C_MAX{1'b0}};
          state <= (|nonempty) ? S_REL : S_EMIT0;
        end
        S_REL: begin
          walk();
          if (!keep) site[sel_r[RI_W-1:0]][sel_c[CI_W-1:0]] <= 1'b0;
          if (!has_next) state <= S_EMIT0;
        end
        S_EMIT0:
          if (|nonempty) begin_site();
          else end_frame();
        S_SQRT: begin
          rad <= rad << 2;
          root <= {root[MAG_W-2:0], sq_ge};
          rem <= sq_ge ? sq_diff[MAG_W+1:0] : sq_r[MAG_W+1:0];
          cnt <= cnt + 5'd1;
          if (cnt == SQ_LAST) state <= S_GSCALE;
        end
        S_GSCALE: begin
          out_value <= g_out;
          state <= S_OUT;
        end
        S_OUT: if (out_ready) begin
          if ((|row_left) || (|col_left)) begin_site();
          else end_frame();
        end
        default: state <= S_IN;
      endcase
    end
  end
endmodule
