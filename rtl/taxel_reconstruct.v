`default_nettype none
// taxel_reconstruct: the streaming block of hls/taxel_reconstruct.h with the
// ghost filter's active-site mask (hls/dtmf_chain.h: taxel = g at an active
// site, else 0). Bit-exact with TaxelReconstruct<R_MAX, C_MAX>::lines and
// ::value and with GhostFilter::release as DtmfChain uses them (formats,
// rounding and saturation are stated in the kernel's header):
//   root_k = isqrt(mag_k << 14)                      (one per line)
//   g_ij   = sat16((root_i root_j recip + 2^(s-1)) >> s),  s = recip_shift + 14
//   site_ij = mask_ij && g_ij >= release             (the release step)
//   out_g  = (!ghost || site_ij) ? g_ij : 0
//
// A frame: (1) the K = rows + cols magnitudes {k, mag, last} in, rows
// first, one a clock (in_k is the line, the kernel's mag[k]; a k >= rows +
// cols is dropped; last on the frame's final magnitude; every line comes
// every frame: a missing one keeps its stored value, a column's with the
// recip it was stored with, where the kernel would rescale it). Each goes
// through the pipelined root (isqrt_pipe, 15 stages); a row's root is kept in the
// row RAM (R_MAX x 15 bits), a column's root is multiplied by recip once
// (c_j = root_j recip < 2^30, exact) and kept in the column RAM
// (C_MAX x 30 bits). (2) Once the last root is stored and the frame's sites
// are in (sites_done, below), the taxels out row-major, one a clock:
// {i, j, g, site, last}, last on (rows-1, cols-1). g = root_i c_j rounded:
// the product root_i root_j recip is associative and exact, so one 15 x 30
// multiply per taxel gives the kernel's value (one 15 x 30 multiplier: 2
// MULT18X18D on the ECP5). Off the mask with ghost on there is no product:
// the multiplier's operands are not loaded. The same multiplier makes the
// line products of phase 1.
//
// Active-site mask: one bit per taxel in the mask RAM (R_MAX * C_MAX bits,
// address i * C_MAX + j; a DP16KD at 64 x 64), written through mask_we/mask_addr/mask_din by its
// owner (the control plane or a ghost-filter block): the sites after the
// ghost filter's frame() step for this frame, before its release step. The
// block does the release step itself, per taxel (site = mask && g >=
// release) and reports it as out_site; the owner clears the sites that were
// in the mask and come out with out_site = 0 before it adds the next
// frame's. The owner writes the mask after the previous frame's last taxel
// was taken and then pulses sites_done (one clock, or holds it high: a
// static mask, or ghost = 0); the taxel phase starts only after it.
// With ghost = 0 every taxel passes (out_g = g) and out_site is still
// mask && g >= release.
//
// Configuration (cfg_*): as the kernel's configure() accepts (rows 1..R_MAX,
// cols 1..C_MAX, recip 1..32767, recip_shift 0..31); held stable from a
// frame's first magnitude to its last taxel's handshake.
//
// Timing (no stalls): magnitudes are taken one a clock while in_ready
// (phase 1); the first taxel's out_valid rises 25 clocks after the clock
// that took the last magnitude (15 root stages; the line product's
// operands, multiply and write; the phase change; 6 output stages), or 7
// clocks after sites_done if that comes later; then one taxel a clock,
// rows x cols clocks. in_ready rises again on the clock after the last
// taxel's handshake: a frame every K + rows cols + 24 clocks (4248 for
// 64 x 64). Output back-pressure: en_o = !out_valid || out_ready moves the
// whole output pipeline (as in rtl/carrier_magnitude.v).
module taxel_reconstruct #(
    parameter integer R_MAX = 3,
    parameter integer C_MAX = 3,
    parameter integer RA = (R_MAX > 1) ? $clog2(R_MAX) : 1,
    parameter integer CA = (C_MAX > 1) ? $clog2(C_MAX) : 1,
    parameter integer MA = (R_MAX * C_MAX > 1) ? $clog2(R_MAX * C_MAX) : 1
) (
    input  wire          clk,
    input  wire          rst,
    // Per-frame configuration.
    input  wire [7:0]    cfg_rows,
    input  wire [7:0]    cfg_cols,
    input  wire [14:0]   cfg_recip,        // 1..32767
    input  wire [4:0]    cfg_recip_shift,
    input  wire          cfg_ghost,
    input  wire [15:0]   cfg_release,
    // Magnitudes.
    input  wire          in_valid,
    output wire          in_ready,
    input  wire [7:0]    in_k,
    input  wire [15:0]   in_mag,
    input  wire          in_last,
    // Active-site mask.
    input  wire          mask_we,
    input  wire [MA-1:0] mask_addr,
    input  wire          mask_din,
    input  wire          sites_done,
    // Taxels.
    output reg           out_valid,
    input  wire          out_ready,
    output reg  [7:0]    out_i,
    output reg  [7:0]    out_j,
    output reg  [15:0]   out_g,
    output reg           out_site,
    output reg           out_last
);
  // The kernel's static_assert, and the address widths the caller may set.
  generate
    if (R_MAX < 1 || C_MAX < 1 || R_MAX + C_MAX > 255 || (1 << RA) < R_MAX ||
        (1 << CA) < C_MAX || (1 << MA) < R_MAX * C_MAX) begin : g_bad
      taxel_reconstruct_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  localparam [1:0] S_LINES = 2'd0, S_DRAIN = 2'd1, S_TAXELS = 2'd2;
  reg [1:0] state;
  reg sites_in;  // sites_done seen for this frame

  wire en_o = !out_valid || out_ready;
  assign in_ready = (state == S_LINES);
  wire in_hs = in_valid && in_ready;

  // ---- Phase 1: line roots.
  wire r_v, r_busy;
  wire [14:0] r_root;
  wire [7:0] r_k;
  isqrt_pipe #(.W(15), .SW(8)) u_root (
      .clk(clk), .rst(rst), .en(1'b1), .in_valid(in_hs), .in_rad({in_mag, 14'd0}),
      .in_side(in_k), .out_valid(r_v), .out_root(r_root), .out_side(r_k), .busy(r_busy));
  wire [8:0] r_kc = {1'b0, r_k} - {1'b0, cfg_rows};   // column index when >= 0
  wire r_row = r_v && r_k < cfg_rows;
  wire r_col = r_v && !r_kc[8] && r_kc[7:0] < cfg_cols;

  (* no_rw_check *) reg [14:0] row_mem [0:R_MAX-1];
  (* no_rw_check *) reg [29:0] col_mem [0:C_MAX-1];
  (* no_rw_check *) reg mask_mem [0:R_MAX*C_MAX-1];

  // The multiplier: phase 1 recip x root_j (column products), phase 2
  // root_i x c_j (taxels).
  reg [14:0] rr_q;     // phase 2: root_i
  reg [29:0] cq_q;     // phase 2: c_j
  reg mk1;             // phase 2: the mask bit of the taxel in rr_q, cq_q
  wire taxels = (state == S_TAXELS);
  wire [14:0] mul_a = taxels ? rr_q : cfg_recip[14:0];
  wire [29:0] mul_b = taxels ? cq_q : {15'd0, r_root};
  wire mul_en = taxels ? en_o : 1'b1;
  // Operands registered first: the column RAM's read (a block RAM's
  // clock-to-out) and the DSP then each have a clock of their own.
  reg [14:0] ma_q;
  reg [29:0] mb_q;
  reg [44:0] m_q;
  reg la_q, lv_q;      // ma/mb, m_q: a column product to store
  reg [CA-1:0] lcola_q, lcol_q;
  always @(posedge clk) begin
    // No product off the mask (ghost on): the operands hold, the DSP does
    // not toggle; that taxel's g is never used (out_g 0, out_site 0).
    if (mul_en && (!taxels || !cfg_ghost || mk1)) begin
      ma_q <= mul_a;
      mb_q <= mul_b;
    end
    if (mul_en) m_q <= ma_q * mb_q;
    if (r_row) row_mem[r_k[RA-1:0]] <= r_root;
    lcola_q <= r_kc[CA-1:0];
    lcol_q <= lcola_q;
    if (lv_q) col_mem[lcol_q] <= m_q[29:0];
    if (mask_we) mask_mem[mask_addr] <= mask_din;
    if (rst) begin
      la_q <= 1'b0;
      lv_q <= 1'b0;
    end else begin
      la_q <= r_col && !taxels;
      lv_q <= la_q;
    end
  end

  // ---- Phase 2: taxels. Stage 1 reads the RAMs, 2 registers the
  // multiplier's operands, 3 multiplies, 4 adds the rounding constant, 5
  // shifts and saturates, 6 is the output (stages 2 and 3 are ma_q/mb_q and
  // m_q above; a, 2 .. 4 below are their companions).
  reg [RA-1:0] ti;
  reg [CA-1:0] tj;
  reg [MA-1:0] row_base;   // i * C_MAX
  reg issuing;             // taxels left to issue this frame
  wire [7:0] rows_m1 = cfg_rows - 8'd1, cols_m1 = cfg_cols - 8'd1;
  wire t_lastcol = {{(8-CA){1'b0}}, tj} == cols_m1;
  wire t_lastrow = {{(8-RA){1'b0}}, ti} == rows_m1;
  reg v1, va, v2, v3, v4;
  reg [RA-1:0] i1, ia, i2, i3, i4;
  reg [CA-1:0] j1, ja, j2, j3, j4;
  reg l1, la, l2, l3, l4, mka, mk2, mk3, mk4;
  reg [31:0] s3;       // (product + 2^(s-1)) >> 14
  reg [15:0] g4;
  // The rounding constant 2^(s-1), s = recip_shift + 14: at most 2^44.
  wire [45:0] half = 46'd1 << ({1'b0, cfg_recip_shift} + 6'd13);
  // The low 14 bits of the rounded sum are below every shift (s >= 14).
  /* verilator lint_off UNUSEDSIGNAL */
  wire [45:0] sum = {1'b0, m_q} + half;
  /* verilator lint_on UNUSEDSIGNAL */
  wire [31:0] shifted = s3 >> cfg_recip_shift;
  wire [15:0] gsat = (|shifted[31:16]) ? 16'hFFFF : shifted[15:0];
  wire site4 = mk4 && g4 >= cfg_release;

  always @(posedge clk) begin
    if (en_o) begin
      rr_q <= row_mem[ti];
      cq_q <= col_mem[tj];
      mk1 <= mask_mem[row_base + {{(MA-CA){1'b0}}, tj}];
      i1 <= ti;
      j1 <= tj;
      l1 <= t_lastrow && t_lastcol;
      ia <= i1; ja <= j1; la <= l1; mka <= mk1;
      i2 <= ia; j2 <= ja; l2 <= la; mk2 <= mka;
      s3 <= sum[45:14];
      i3 <= i2; j3 <= j2; l3 <= l2; mk3 <= mk2;
      g4 <= gsat;
      i4 <= i3; j4 <= j3; l4 <= l3; mk4 <= mk3;
      out_i <= {{(8-RA){1'b0}}, i4};
      out_j <= {{(8-CA){1'b0}}, j4};
      out_g <= (!cfg_ghost || site4) ? g4 : 16'd0;
      out_site <= site4;
      out_last <= l4;
    end
    if (rst) begin
      v1 <= 1'b0; va <= 1'b0; v2 <= 1'b0; v3 <= 1'b0; v4 <= 1'b0;
      out_valid <= 1'b0;
    end else if (en_o) begin
      v1 <= taxels && issuing;
      va <= v1; v2 <= va; v3 <= v2; v4 <= v3;
      out_valid <= v4;
    end
  end

  // ---- Control.
  always @(posedge clk) begin
    if (rst) begin
      state <= S_LINES;
      sites_in <= 1'b0;
      issuing <= 1'b0;
      ti <= {RA{1'b0}};
      tj <= {CA{1'b0}};
      row_base <= {MA{1'b0}};
    end else begin
      if (sites_done) sites_in <= 1'b1;
      case (state)
        S_LINES:
          if (in_hs && in_last) state <= S_DRAIN;
        S_DRAIN:
          // The last root and column product are stored.
          if (!r_busy && !la_q && !lv_q && (sites_in || sites_done)) begin
            state <= S_TAXELS;
            issuing <= 1'b1;
            ti <= {RA{1'b0}};
            tj <= {CA{1'b0}};
            row_base <= {MA{1'b0}};
          end
        default: begin  // S_TAXELS
          if (en_o && issuing) begin
            if (!t_lastcol) begin
              tj <= tj + 1'b1;
            end else if (!t_lastrow) begin
              tj <= {CA{1'b0}};
              ti <= ti + 1'b1;
              row_base <= row_base + MA'(C_MAX);
            end else begin
              issuing <= 1'b0;
            end
          end
          if (out_valid && out_ready && out_last) begin
            state <= S_LINES;
            sites_in <= 1'b0;
          end
        end
      endcase
    end
  end
endmodule
`default_nettype wire
