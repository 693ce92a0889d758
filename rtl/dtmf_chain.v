`default_nettype none
// dtmf_chain: the streaming datapath of hls/dtmf_chain.h for the large
// FPGAs, one element a clock from a frame's carrier tokens to its packet
// bytes. The frame engine (rtl/frame_engine.v running
// rtl/ucode/dtmf_chain.fe) is the chain's other form: the whole chain
// where the chip is small, and the control plane beside this block where
// it is large. The name is the kernel's: this module and the microprogram
// are two implementations of the one spec, as rtl/carrier_magnitude.v and
// the microcode's carrier_magnitude routine are of hls/carrier_magnitude.h.
//
// Per frame, in DtmfChain::frame's order (the control plane's part named):
//   tokens {k, re, im, last} (the demixed window sums, or the bank's when
//       there is no demixing; k < K = R + C, rows first)
//   -> carrier_magnitude (ACC_W-bit sums, 16-bit magnitudes >> MAG_SHIFT)
//   -> the magnitude RAM (K x 16 bits, read port mag_raddr / mag_rdata, one
//       clock) and taxel_reconstruct's line roots
//   control plane: reads the K magnitudes (mag_ready high), runs the ghost
//       filter's frame() step (the O(K^2) pairing), writes the sites it
//       adds into the mask (mask_we, address i C + j, din 1) and pulses
//       sites_done; sends the AMPLITUDES packet from the same magnitudes
//   -> taxel_reconstruct: the taxels, row-major, one a clock, g = 0 off a
//       site when cfg_ghost; the release step per taxel (site = mask && g
//       >= release)
//   -> taxel_packetizer: TAXELS_DENSE / TAXELS_SPARSE as the frame's header
//       (hdr_*, from the control plane every frame, none-of-both included:
//       its taxels are consumed either way) asks, whole packets or none
//       against out_free, into the output FIFO port out_*.
// The mask RAM is the ghost filter's site state: the block clears the bit
// of every taxel that comes out with site = 0 (GhostFilter::release), so
// after a frame the mask holds exactly the filter's sites and the control
// plane only adds the next frame's new ones (GhostFilter::frame only ever
// sets sites; setting one that is set is harmless). A ghost reset clears
// all R C bits through mask_we. The control plane writes the mask only
// while no taxel is in flight: from the frame's last taxel (mag_ready
// falls) until it pulses sites_done (an assertion in simulation).
//
// Magnitude RAM: written as taxel_reconstruct takes each magnitude, which it
// does only between frames' taxel phases, so it holds a frame's magnitudes
// from mag_ready's rise (the frame's last magnitude taken) to its fall (the
// frame's last taxel taken by the packetizer).
//
// Parameters: R, C the skin (the packets' rows and cols; R C <= 16383 and
// 1..255 each, taxel_packetizer's; R + C <= 255, taxel_reconstruct's k),
// ACC_W and MAG_SHIFT the kernel's CarrierMagnitude<ACC_W, 16, MAG_SHIFT>
// (hls/dtmf_chain.h: ACC_W = DEMIX_W = 24, MAG_SHIFT = DtmfChainSizes's).
//
// Timing (nothing stalls: tokens offered every clock, sites_done high, the
// header ready, out_ready high, room in the FIFO), from the blocks' stated
// latencies: a token's magnitude reaches taxel_reconstruct 21 clocks after
// it is taken (carrier_magnitude, MAG_W + 5); the first taxel comes 25
// clocks after the last magnitude, then one a clock, and the next frame's
// first magnitude is taken on the clock after the last taxel's handshake:
// a frame every K + R C + 24 clocks with no packet (the tokens of the next
// frame wait in carrier_magnitude's pipeline meanwhile). A dense packet
// takes a taxel every 2 clocks (two bytes), and the sparse packet follows
// the last taxel; tests/rtl/dtmf_chain_test.cpp states and checks the
// periods for each case.
module dtmf_chain #(
    parameter integer R = 3,
    parameter integer C = 3,
    parameter integer ACC_W = 24,
    parameter integer MAG_SHIFT = 0,
    parameter integer KA = (R + C > 1) ? $clog2(R + C) : 1,   // magnitude address bits
    parameter integer MA = (R * C > 1) ? $clog2(R * C) : 1    // mask address bits
) (
    input  wire              clk,
    input  wire              rst,
    // Configuration, held stable while a frame is in flight.
    input  wire [14:0]       cfg_recip,        // 1..32767
    input  wire [4:0]        cfg_recip_shift,
    input  wire              cfg_ghost,
    input  wire [15:0]       cfg_release,
    // Carrier tokens.
    input  wire              in_valid,
    output wire              in_ready,
    input  wire [7:0]        in_k,
    input  wire [ACC_W-1:0]  in_re,            // signed
    input  wire [ACC_W-1:0]  in_im,            // signed
    input  wire              in_last,
    // Magnitudes for the control plane.
    output reg               mag_ready,
    input  wire [KA-1:0]     mag_raddr,
    output reg  [15:0]       mag_rdata,
    // Active-site mask from the control plane.
    input  wire              mask_we,
    input  wire [MA-1:0]     mask_addr,
    input  wire              mask_din,
    input  wire              sites_done,
    // The frame's taxel packets: one header a frame.
    input  wire              hdr_valid,
    output wire              hdr_ready,
    input  wire [31:0]       hdr_t,
    input  wire              hdr_dense,
    input  wire              hdr_sparse,
    input  wire [15:0]       hdr_sparse_min,
    // The output FIFO's write port.
    input  wire [15:0]       out_free,
    output wire              out_valid,
    input  wire              out_ready,
    output wire [7:0]        out_data,
    output wire              dropped,          // a packet left out (one clock)
    // Each taxel as the packetizer takes it (for status counters and tests).
    output wire              tax_valid,
    output wire              tax_site,
    output wire              idle              // no frame in flight, no packet going out
);
  localparam integer K = R + C;
  localparam integer T = R * C;
  generate
    if (R < 1 || R > 255 || C < 1 || C > 255 || K > 255 || T > 16383 || ACC_W < 2 ||
        ACC_W > 32 || MAG_SHIFT < 0 || MAG_SHIFT > ACC_W || (1 << KA) < K ||
        (1 << MA) < T) begin : g_bad_params
      dtmf_chain_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  // ---- carrier_magnitude.
  wire       m_valid, m_ready, m_last;
  wire [7:0] m_k;
  wire [15:0] m_mag;
  carrier_magnitude #(.ACC_W(ACC_W), .MAG_W(16), .SHIFT(MAG_SHIFT)) u_mag (
      .clk(clk), .rst(rst), .in_valid(in_valid), .in_ready(in_ready), .in_k(in_k),
      .in_re(in_re), .in_im(in_im), .in_last(in_last), .out_valid(m_valid),
      .out_ready(m_ready), .out_k(m_k), .out_mag(m_mag), .out_last(m_last));
  wire m_take = m_valid && m_ready;

  // ---- The magnitude RAM.
  reg [15:0] mag_mem [0:K-1];
  always @(posedge clk) begin
    if (m_take && m_k < 8'(K)) mag_mem[m_k[KA-1:0]] <= m_mag;
    mag_rdata <= mag_mem[mag_raddr];
  end

  // ---- taxel_reconstruct, with the release step's clears muxed onto the
  // mask's write port.
  wire        t_valid, t_ready, t_site, t_last;
  wire [7:0]  t_i, t_j;
  wire [15:0] t_g;
  wire t_take = t_valid && t_ready;
  reg [MA-1:0] t_n;  // the taxel's index, row-major
  wire rel_we = t_take && !t_site;
  taxel_reconstruct #(.R_MAX(R), .C_MAX(C), .MA(MA)) u_tax (
      .clk(clk), .rst(rst), .cfg_rows(8'(R)), .cfg_cols(8'(C)), .cfg_recip(cfg_recip),
      .cfg_recip_shift(cfg_recip_shift), .cfg_ghost(cfg_ghost), .cfg_release(cfg_release),
      .in_valid(m_valid), .in_ready(m_ready), .in_k(m_k), .in_mag(m_mag), .in_last(m_last),
      .mask_we(mask_we || rel_we), .mask_addr(mask_we ? mask_addr : t_n),
      .mask_din(mask_we ? mask_din : 1'b0), .sites_done(sites_done),
      .out_valid(t_valid), .out_ready(t_ready), .out_i(t_i), .out_j(t_j), .out_g(t_g),
      .out_site(t_site), .out_last(t_last));
  assign tax_valid = t_take;
  assign tax_site = t_site;

  always @(posedge clk) begin
    if (rst) begin
      t_n <= {MA{1'b0}};
      mag_ready <= 1'b0;
    end else begin
      if (t_take) t_n <= t_last ? {MA{1'b0}} : t_n + 1'b1;
      if (m_take && m_last) mag_ready <= 1'b1;
      else if (t_take && t_last) mag_ready <= 1'b0;
    end
  end

  // ---- taxel_packetizer.
  wire p_idle;
  taxel_packetizer #(.R(R), .C(C)) u_pkt (
      .clk(clk), .rst(rst), .hdr_valid(hdr_valid), .hdr_ready(hdr_ready), .hdr_t(hdr_t),
      .hdr_dense(hdr_dense), .hdr_sparse(hdr_sparse), .hdr_sparse_min(hdr_sparse_min),
      .in_valid(t_valid), .in_ready(t_ready), .in_value(t_g), .in_row(t_i), .in_col(t_j),
      .in_last(t_last), .out_free(out_free), .out_valid(out_valid), .out_ready(out_ready),
      .out_data(out_data), .dropped(dropped), .idle(p_idle));

  // In flight: a token in carrier_magnitude's pipeline is not visible here;
  // idle covers the rest (taxel_reconstruct between frames, nothing to send).
  assign idle = p_idle && !mag_ready && !m_valid && !t_valid;

`ifndef SYNTHESIS
  // The control plane's mask writes stay out of the taxel phase (a write
  // there would race the release clears and the taxels' reads).
  reg sites_given;
  always @(posedge clk) begin
    if (rst) begin
      sites_given <= 1'b0;
    end else begin
      if (sites_done && mag_ready) sites_given <= 1'b1;
      if (t_take && t_last) sites_given <= 1'b0;
      if (mask_we && sites_given)
        $error("dtmf_chain: mask written after sites_done, before the frame's last taxel");
    end
  end
`endif
endmodule
`default_nettype wire
