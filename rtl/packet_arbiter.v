`default_nettype none
// packet_arbiter: NS packet byte streams in, one out, whole packets at a
// time, so several tops can share one link_framer (one seq counter) and one
// UART (rtl/mixed_top.v).
//
// Each input carries whole packets as link_framer takes them: type, t (4
// bytes LE), len (2 bytes LE), then exactly len payload bytes. Once a
// source's first byte is granted, that source alone is passed through
// (valid/ready straight through, no buffering) until its packet's last byte;
// a source that pauses mid-packet holds the output. Between packets the
// grant goes round robin, starting after the source served last, so no
// source can starve another: each waits at most NS - 1 packets. Choosing a
// source takes one idle clock per packet (the grant is registered).
module packet_arbiter #(
    parameter integer NS = 2
) (
    input  wire            clk,
    input  wire            rst,
    input  wire [NS-1:0]   s_valid,
    output wire [NS-1:0]   s_ready,
    input  wire [NS*8-1:0] s_data,
    output wire            m_valid,
    input  wire            m_ready,
    output wire [7:0]      m_data
);
  localparam integer GW = (NS > 1) ? $clog2(NS) : 1;
  generate
    if (NS < 1 || NS > 16) begin : g_bad_params
      packet_arbiter_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  reg          busy;     // a packet of source g is being passed
  reg [GW-1:0] g;
  reg [2:0]    hidx;     // header byte being passed (0..6), 7 once in the payload
  reg [7:0]    len_lo;
  reg [15:0]   left;     // payload bytes still to pass

  wire [7:0] data_g = s_data[g*8 +: 8];
  assign m_valid = busy && s_valid[g];
  assign m_data = data_g;
  genvar i;
  generate
    for (i = 0; i < NS; i = i + 1) begin : g_ready
      assign s_ready[i] = busy && g == GW'(i) && m_ready;
    end
  endgenerate
  wire fire = m_valid && m_ready;
  wire [15:0] len = {data_g, len_lo};  // at header byte 6
  wire last = (hidx == 3'd6 && len == 16'd0) || (hidx == 3'd7 && left == 16'd1);

  // The next source, round robin after g: the first valid one of g+1, g+2, ...
  reg          pick_any;
  reg [GW-1:0] pick;
  integer k;
  always @(*) begin
    pick_any = 1'b0;
    pick = g;
    for (k = NS; k >= 1; k = k - 1)
      if (s_valid[(32'(g) + k) % NS]) begin
        pick_any = 1'b1;
        pick = GW'((32'(g) + k) % NS);
      end
  end

  always @(posedge clk) begin
    if (rst) begin
      busy <= 1'b0;
      g <= {GW{1'b0}};
      hidx <= 3'd0;
      len_lo <= 8'd0;
      left <= 16'd0;
    end else if (!busy) begin
      if (pick_any) begin
        busy <= 1'b1;
        g <= pick;
        hidx <= 3'd0;
      end
    end else if (fire) begin
      if (hidx == 3'd5) len_lo <= data_g;
      if (hidx == 3'd6) left <= len;
      if (hidx == 3'd7) left <= left - 16'd1;
      if (hidx != 3'd7) hidx <= hidx + 3'd1;
      if (last) busy <= 1'b0;
    end
  end
endmodule
`default_nettype wire
