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
//       against out_free
//   -> with cfg_neurons, the same taxels (a fork: a taxel moves when both
//       take it) into layer 0, izhikevich_pipe (receptor n = taxel n, x =
//       g) -> its spike flags into synapse_weights (3x3, line buffers) ->
//       layer 1, izhikevich_pipe (neuron n = taxel n, x = the weighted sum)
//   -> spike_encoder: when the header asks to record (hdr_spikes), OP_FRAME
//       (t), layer 0's spikes as they come, layer 1's (kept in a RAM of T
//       neuron numbers until layer 0's last is out: the kernel's order),
//       and OP_CLOSE when the header ends the window (hdr_close): the
//       SPIKES packet, whole or none
//   -> packet_arbiter: the packetizer's and the encoder's packets onto the
//       one output FIFO port out_*, whole packets, round robin (a clock a
//       packet for the grant).
// With neurons, a frame's header is taken only once the previous frame's
// events and SPIKES packet are out: else that packet, waiting at the
// arbiter behind this frame's dense packet, would hold the encoder, layer
// 0 would wait for the encoder and the dense packet for layer 0's taxels.
// Both sources check out_free for their own packet only: a packet of one
// that waits for the other's may find less room than it checked, and then
// waits on out_ready (no packet is cut: the FIFO back-pressures).
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
// (hls/dtmf_chain.h: ACC_W = DEMIX_W = 24, MAG_SHIFT = DtmfChainSizes's),
// MAX_SPIKES the spike encoder's events a window (DtmfChainSizes's).
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
// periods for each case, and that the layers (spikes not recorded) add
// nothing to them: they finish a frame within the K + 25 clocks before the
// next frame's taxels. Recording, the layers' 7 clocks each, the synapse's
// row, the events one a clock after the frame's last layer-1 neuron and
// the SPIKES packet (8 + 5 n clocks) come before the next frame's header
// is taken (not yet stated as a fixed bound).
module dtmf_chain #(
    parameter integer R = 3,
    parameter integer C = 3,
    parameter integer ACC_W = 24,
    parameter integer MAG_SHIFT = 0,
    parameter integer MAX_SPIKES = 256,   // spike events a window (spike_encoder's MAX)
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
    input  wire              cfg_neurons,      // the two layers, the synapse and the spikes
    input  wire [143:0]      cfg_w,            // synapse_weights' nine int16 weights
    // The layers' constant words (hls::neuron_block; nu_cfg_we[l] layer l),
    // written while no frame is in flight; nu_init resets both layers' state
    // (R C clocks, nu_busy).
    input  wire [1:0]        nu_cfg_we,
    input  wire [4:0]        nu_cfg_addr,
    input  wire [31:0]       nu_cfg_data,
    input  wire              nu_init,
    output wire              nu_busy,
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
    input  wire              hdr_spikes,       // record this frame's spikes (neurons and mask bit 2)
    input  wire              hdr_close,        // the spike window ends with this frame
    // The output FIFO's write port.
    input  wire [15:0]       out_free,
    output wire              out_valid,
    input  wire              out_ready,
    output wire [7:0]        out_data,
    output wire              dropped,          // a packet left out (one clock)
    output wire [31:0]       spikes_dropped,   // events past MAX_SPIKES a window (spike_encoder's)
    input  wire              drops_clear,      // zero spikes_dropped
    // Each taxel as the packetizer takes it (for status counters and tests).
    output wire              tax_valid,
    output wire              tax_site,
    output wire              idle,             // no frame in flight, no packet going out
    // The layers, the synapse and the events hold no frame's work: their
    // constants (nu_cfg_*, cfg_w) may change for the next header's frame.
    output wire              layers_idle
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

  // ---- The taxel stream forks to the packetizer and (cfg_neurons) layer 0:
  // a taxel moves when both take it.
  wire p_in_ready, l0_in_ready;
  wire fork_l0 = cfg_neurons;
  assign t_ready = p_in_ready && (!fork_l0 || l0_in_ready);

  // ---- taxel_packetizer.
  wire p_idle, p_valid, p_ready, p_dropped;
  wire [7:0] p_data;
  // A frame's header waits (with neurons) until the previous frame's events
  // and SPIKES packet are out: otherwise that packet, queued at the output
  // behind this frame's dense packet, would hold the encoder, layer 0 would
  // wait for the encoder and the dense packet for layer 0's taxels.
  wire p_hdr_ready, ev_idle;
  assign hdr_ready = p_hdr_ready && (!cfg_neurons || ev_idle);
  taxel_packetizer #(.R(R), .C(C)) u_pkt (
      .clk(clk), .rst(rst), .hdr_valid(hdr_valid && (!cfg_neurons || ev_idle)),
      .hdr_ready(p_hdr_ready), .hdr_t(hdr_t),
      .hdr_dense(hdr_dense), .hdr_sparse(hdr_sparse), .hdr_sparse_min(hdr_sparse_min),
      .in_valid(t_valid && (!fork_l0 || l0_in_ready)), .in_ready(p_in_ready), .in_value(t_g),
      .in_row(t_i), .in_col(t_j), .in_last(t_last), .out_free(out_free), .out_valid(p_valid),
      .out_ready(p_ready), .out_data(p_data), .dropped(p_dropped), .idle(p_idle));

  // ---- The frames' spike records: {t, record, close} per header, for the
  // event sequencer (the packetizer takes frame f + 1's header before the
  // events of frame f are all out at most: two in flight).
  reg [33:0] hq [0:3];
  reg [1:0]  hq_w, hq_r;
  reg [2:0]  hq_n;
  wire hq_push = hdr_valid && hdr_ready && cfg_neurons;
  wire [33:0] hq_head = hq[hq_r];
  wire hq_rec = hq_head[33], hq_close = hq_head[32];
  wire hq_pop;

  // ---- Layer 0: one receptor a taxel, input g.
  localparam integer NB = (T > 1) ? $clog2(T) : 1;
  wire nu_busy0, nu_busy1;
  assign nu_busy = nu_busy0 || nu_busy1;
  wire l0_valid, l0_ready, l0_spike, l0_last;
  wire [NB-1:0] l0_n;
  /* verilator lint_off PINCONNECTEMPTY */
  izhikevich_pipe #(.N(T), .NB(NB)) u_l0 (
      .clk(clk), .rst(rst), .cfg_we(nu_cfg_we[0]), .cfg_addr(nu_cfg_addr),
      .cfg_data(nu_cfg_data), .init(nu_init), .busy(nu_busy0),
      .in_valid(t_valid && fork_l0 && p_in_ready), .in_ready(l0_in_ready),
      .in_n(t_n[NB-1:0]), .in_x({16'd0, t_g}), .in_last(t_last),
      .out_valid(l0_valid), .out_ready(l0_ready), .out_n(l0_n), .out_spike(l0_spike),
      .out_v(), .out_u(), .out_last(l0_last));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- synapse_weights over layer 0's flags, then layer 1.
  wire s_in_ready, s_valid, s_ready, s_last;
  wire signed [19:0] s_x;
  wire l0_to_syn;  // layer 0's output goes on (to the synapse, and its event)
  synapse_weights #(.R(R), .C(C)) u_syn (
      .clk(clk), .rst(rst), .w(cfg_w), .in_valid(l0_to_syn), .in_ready(s_in_ready),
      .in_flag(l0_spike), .out_valid(s_valid), .out_ready(s_ready), .out_x(s_x),
      .out_last(s_last));
  reg [NB-1:0] s_n;  // the synapse output's neuron, row-major
  wire s_take = s_valid && s_ready;
  wire l1_valid, l1_spike, l1_last;
  wire [NB-1:0] l1_n;
  /* verilator lint_off PINCONNECTEMPTY */
  izhikevich_pipe #(.N(T), .NB(NB)) u_l1 (
      .clk(clk), .rst(rst), .cfg_we(nu_cfg_we[1]), .cfg_addr(nu_cfg_addr),
      .cfg_data(nu_cfg_data), .init(nu_init), .busy(nu_busy1),
      .in_valid(s_valid), .in_ready(s_ready), .in_n(s_n), .in_x({{12{s_x[19]}}, s_x}),
      .in_last(s_last), .out_valid(l1_valid), .out_ready(1'b1), .out_n(l1_n),
      .out_spike(l1_spike), .out_v(), .out_u(), .out_last(l1_last));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---- Layer 1's spikes wait (their neuron numbers, at most T a frame)
  // until layer 0's events are out: the SPIKES order is layer 0 then 1.
  reg [NB-1:0] l1q [0:T-1];
  reg [NB:0]   l1q_w, l1q_r;
  reg [NB-1:0] l1q_q;
  reg          l1_done;   // the frame's last layer-1 neuron is out

  // ---- The event sequencer: spike_encoder's commands in the kernel's order.
  localparam [2:0] E_FRAME = 3'd0, E_L0 = 3'd1, E_L1W = 3'd2, E_L1R = 3'd3, E_L1 = 3'd4,
                   E_CLOSE = 3'd5;
  reg [2:0] ev;
  reg        e_valid;
  reg [1:0]  e_op;
  reg        e_layer;
  reg [15:0] e_neuron;
  wire e_ready;
  wire l0_ev = hq_rec && l0_spike;       // layer 0's output makes an event
  wire l1q_any = l1q_r != l1q_w;
  always @(*) begin
    e_valid = 1'b0;
    e_op = 2'd1;
    e_layer = 1'b0;
    e_neuron = 16'(l0_n);
    case (ev)
      E_FRAME: begin e_valid = cfg_neurons && hq_n != 3'd0 && hq_rec; e_op = 2'd0; end
      E_L0: e_valid = l0_valid && s_in_ready && l0_ev;
      E_L1: begin e_valid = l1q_any; e_layer = 1'b1; e_neuron = 16'(l1q_q); end
      E_CLOSE: begin e_valid = hq_rec && hq_close; e_op = 2'd2; end
      default: ;
    endcase
  end
  wire e_take = e_valid && e_ready;
  assign l0_ready = ev == E_L0 && s_in_ready && (!l0_ev || e_ready);
  assign l0_to_syn = ev == E_L0 && l0_valid && (!l0_ev || e_ready);
  wire l0_take = l0_valid && l0_ready;
  assign hq_pop = ev == E_CLOSE && (e_take || !(hq_rec && hq_close));
  wire [NB:0] l1q_rn = l1q_r + {{NB{1'b0}}, e_take && ev == E_L1};

  always @(posedge clk) begin
    if (hq_push) hq[hq_w] <= {hdr_spikes, hdr_close, hdr_t};
    if (l1_valid && l1_spike && hq_rec) l1q[l1q_w[NB-1:0]] <= l1_n;
    l1q_q <= l1q[l1q_rn[NB-1:0]];
    if (rst) begin
      hq_w <= 2'd0;
      hq_r <= 2'd0;
      hq_n <= 3'd0;
      ev <= E_FRAME;
      l1q_w <= {(NB+1){1'b0}};
      l1q_r <= {(NB+1){1'b0}};
      l1_done <= 1'b0;
      s_n <= {NB{1'b0}};
    end else begin
      hq_w <= hq_w + {1'b0, hq_push};
      hq_r <= hq_r + {1'b0, hq_pop};
      hq_n <= hq_n + {2'd0, hq_push} - {2'd0, hq_pop};
      if (s_take) s_n <= s_last ? {NB{1'b0}} : s_n + 1'b1;
      if (l1_valid && l1_spike && hq_rec) l1q_w <= l1q_w + 1'b1;
      if (l1_valid && l1_last) l1_done <= 1'b1;
      l1q_r <= l1q_rn;
      case (ev)
        E_FRAME: if (cfg_neurons && hq_n != 3'd0 && (!hq_rec || e_take)) ev <= E_L0;
        E_L0: if (l0_take && l0_last) ev <= E_L1W;
        E_L1W: if (l1_done) ev <= E_L1R;   // the last write is in: read the head next
        E_L1R: ev <= E_L1;
        E_L1: if (!l1q_any || (e_take && l1q_rn == l1q_w)) ev <= E_CLOSE;
        default: if (hq_pop) begin        // E_CLOSE
          ev <= E_FRAME;
          l1q_w <= {(NB+1){1'b0}};
          l1q_r <= {(NB+1){1'b0}};
          l1_done <= 1'b0;
        end
      endcase
    end
  end

  wire en_valid, en_ready, en_dropped;
  wire [7:0] en_data;
  spike_encoder #(.MAX(MAX_SPIKES)) u_enc (
      .clk(clk), .rst(rst), .in_valid(e_valid), .in_ready(e_ready), .in_op(e_op),
      .in_t(hq_head[31:0]), .in_layer(e_layer), .in_neuron(e_neuron), .out_free(out_free),
      .out_valid(en_valid), .out_ready(en_ready), .out_data(en_data), .dropped(en_dropped),
      .spikes_dropped(spikes_dropped), .clear(drops_clear));

  // ---- One output port, whole packets (packet_arbiter: round robin).
  packet_arbiter #(.NS(2)) u_arb (
      .clk(clk), .rst(rst), .s_valid({en_valid, p_valid}), .s_ready({en_ready, p_ready}),
      .s_data({en_data, p_data}), .m_valid(out_valid), .m_ready(out_ready), .m_data(out_data));
  assign dropped = p_dropped || en_dropped;

  // In flight: a token in carrier_magnitude's pipeline is not visible here;
  // idle covers the rest (taxel_reconstruct between frames, the layers and
  // the events done, nothing to send).
  assign ev_idle = ev == E_FRAME && hq_n == 3'd0 && e_ready;
  assign layers_idle = ev_idle;
  assign idle = p_idle && !mag_ready && !m_valid && !t_valid && !p_valid && !en_valid &&
                (!cfg_neurons || ev_idle);

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
