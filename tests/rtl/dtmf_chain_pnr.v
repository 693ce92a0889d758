// dtmf_chain_pnr: rtl/dtmf_chain.v with its ports folded onto a few pins, for
// place and route (tests/rtl/dtmf_chain_test.cmake): the datapath has more
// ports than a package has pins. Every input comes from a serial-in shift
// register and every output is XOR-folded into one registered pin, so
// nothing of the datapath is optimised away and every input-to-output path
// starts and ends at a flip-flop; the wrapper itself costs the shift
// register (one flip-flop an input bit) and the fold.
`default_nettype none

module dtmf_chain_pnr #(
    parameter integer R = 64,
    parameter integer C = 64,
    parameter integer MAG_SHIFT = 4,
    parameter integer MAX_SPIKES = 1024
) (
    input  wire clk,
    input  wire rst,
    input  wire din,
    output reg  dout
);
  localparam integer KA = (R + C > 1) ? $clog2(R + C) : 1;
  localparam integer MA = (R * C > 1) ? $clog2(R * C) : 1;
  localparam integer IW = 15 + 5 + 1 + 16 + 1 + 144 + 2 + 5 + 32 + 1 + 1 + 8 + 24 + 24 + 1 + KA + 1 +
                          MA + 1 + 1 + 1 + 32 + 1 + 1 + 16 + 1 + 1 + 16 + 1 + 1;
  reg [IW-1:0] sr;
  always @(posedge clk) sr <= {sr[IW-2:0], din};

  wire [14:0] cfg_recip;
  wire [4:0] cfg_recip_shift;
  wire cfg_ghost, cfg_neurons, nu_init, in_valid, in_last, mask_we, mask_din, sites_done;
  wire hdr_valid, hdr_dense, hdr_sparse, hdr_spikes, hdr_close, out_ready, drops_clear;
  wire [15:0] cfg_release, hdr_sparse_min, out_free;
  wire [143:0] cfg_w;
  wire [1:0] nu_cfg_we;
  wire [4:0] nu_cfg_addr;
  wire [31:0] nu_cfg_data, hdr_t;
  wire [7:0] in_k;
  wire [23:0] in_re, in_im;
  wire [KA-1:0] mag_raddr;
  wire [MA-1:0] mask_addr;
  assign {cfg_recip, cfg_recip_shift, cfg_ghost, cfg_release, cfg_neurons, cfg_w, nu_cfg_we,
          nu_cfg_addr, nu_cfg_data, nu_init, in_valid, in_k, in_re, in_im, in_last, mag_raddr,
          mask_we, mask_addr, mask_din, sites_done, hdr_valid, hdr_t, hdr_dense, hdr_sparse,
          hdr_sparse_min, hdr_spikes, hdr_close, out_free, out_ready, drops_clear} = sr;

  wire nu_busy, in_ready, mag_ready, hdr_ready, out_valid, dropped, tax_valid, tax_site, idle;
  wire layers_idle;
  wire [15:0] mag_rdata;
  wire [7:0] out_data;
  wire [31:0] spikes_dropped;
  dtmf_chain #(.R(R), .C(C), .MAG_SHIFT(MAG_SHIFT), .MAX_SPIKES(MAX_SPIKES)) u_dp (
      .clk(clk), .rst(rst), .cfg_recip(cfg_recip), .cfg_recip_shift(cfg_recip_shift),
      .cfg_ghost(cfg_ghost), .cfg_release(cfg_release), .cfg_neurons(cfg_neurons),
      .cfg_w(cfg_w), .nu_cfg_we(nu_cfg_we), .nu_cfg_addr(nu_cfg_addr),
      .nu_cfg_data(nu_cfg_data), .nu_init(nu_init), .nu_busy(nu_busy), .in_valid(in_valid),
      .in_ready(in_ready), .in_k(in_k), .in_re(in_re), .in_im(in_im), .in_last(in_last),
      .mag_ready(mag_ready), .mag_raddr(mag_raddr), .mag_rdata(mag_rdata), .mask_we(mask_we),
      .mask_addr(mask_addr), .mask_din(mask_din), .sites_done(sites_done),
      .hdr_valid(hdr_valid), .hdr_ready(hdr_ready), .hdr_t(hdr_t), .hdr_dense(hdr_dense),
      .hdr_sparse(hdr_sparse), .hdr_sparse_min(hdr_sparse_min), .hdr_spikes(hdr_spikes),
      .hdr_close(hdr_close), .out_free(out_free), .out_valid(out_valid),
      .out_ready(out_ready), .out_data(out_data), .dropped(dropped),
      .spikes_dropped(spikes_dropped), .drops_clear(drops_clear), .tax_valid(tax_valid),
      .tax_site(tax_site), .layers_idle(layers_idle),
      .idle(idle));
  always @(posedge clk)
    dout <= ^{nu_busy, in_ready, mag_ready, mag_rdata, hdr_ready, out_valid, out_data, dropped,
              spikes_dropped, tax_valid, tax_site, idle, layers_idle};
endmodule
`default_nettype wire
