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
`ifdef FORMAL
  // Properties (tests/formal/packet_arbiter.sby, docs/formal.md).
  // Assumed, of each source only: whole packets (type, t, len, len
  // payload bytes) and valid/ready (valid and data held until taken);
  // the first clock resets. m_ready is free.
  reg f_past = 1'b0;
  always @(posedge clk) f_past <= 1'b1;
  always @(*) if (!f_past) assume (rst);

  // Each source's own position in its packet, counted here from its
  // handshakes alone: header byte 0..6, then 7 with f_left payload bytes
  // to go. A source at 0 is between packets.
  localparam [4:0] F_NS = NS;
  wire [GW-1:0] f_grant = pick;
  wire f_grant_now = !busy && pick_any && !rst;
  genvar fi;
  generate
    for (fi = 0; fi < NS; fi = fi + 1) begin : g_formal_src
      reg [2:0]  f_hidx;
      reg [7:0]  f_lo;
      reg [15:0] f_left;
      reg [3:0]  f_wait;  // packets granted to others while this one waits
      wire take = s_valid[fi] && s_ready[fi];
      wire src_last = (f_hidx == 3'd6 && {s_data[fi*8 +: 8], f_lo} == 16'd0) ||
                      (f_hidx == 3'd7 && f_left == 16'd1);
      // Waiting: its next packet's first byte is offered and not yet granted.
      wire waiting = s_valid[fi] && f_hidx == 3'd0 && !(busy && g == GW'(fi));
      always @(posedge clk)
        if (f_past && !$past(rst) && $past(s_valid[fi] && !s_ready[fi]))
          assume (s_valid[fi] && s_data[fi*8 +: 8] == $past(s_data[fi*8 +: 8]));
      always @(posedge clk)
        if (rst) begin
          f_hidx <= 3'd0;
          f_left <= 16'd0;
          f_lo <= 8'd0;
          f_wait <= 4'd0;
        end else begin
          if (take) begin
            if (f_hidx == 3'd5) f_lo <= s_data[fi*8 +: 8];
            if (f_hidx == 3'd6) f_left <= {s_data[fi*8 +: 8], f_lo};
            if (f_hidx == 3'd7) f_left <= f_left - 16'd1;
            f_hidx <= src_last ? 3'd0 : (f_hidx == 3'd7 ? 3'd7 : f_hidx + 3'd1);
          end
          if (f_grant_now && f_grant == GW'(fi)) f_wait <= 4'd0;
          else if (f_grant_now && waiting) f_wait <= f_wait + 4'd1;
          else if (!waiting) f_wait <= 4'd0;
        end
      // Round-robin distance from the last grant to this source (1..NS).
      localparam [4:0] F_I = fi;
      wire [4:0] f_g = {{(5 - GW){1'b0}}, g};
      wire [4:0] f_w = {1'b0, f_wait};
      wire [4:0] dist = (F_I > f_g) ? F_I - f_g : F_I + F_NS - f_g;
      always @(*)
        if (f_past && !rst) begin
          // One packet at a time: a source is mid-packet only while it
          // holds the grant, and then exactly where the arbiter counts.
          if (!(busy && g == GW'(fi))) assert (f_hidx == 3'd0);
          else begin
            assert (f_hidx == hidx);
            if (hidx == 3'd6) assert (f_lo == len_lo);
            if (hidx == 3'd7) assert (f_left == left && left != 16'd0);
          end
          // The waiting bound: at most NS - 1 packets of others.
          assert (f_w <= F_NS - 5'd1);
          if (waiting) assert (f_w + dist <= F_NS);
          else assert (f_wait == 4'd0);
        end
      always @(posedge clk)
        if (f_past && !rst) cover (waiting && f_w == F_NS - 5'd1);  // the bound is met
    end
  endgenerate

  // The output is source g's stream, untouched: no byte of another source
  // and nothing while no packet is granted.
  always @(*)
    if (f_past && !rst) begin
      assert (32'(g) < NS);
      assert (m_valid == (busy && s_valid[g]));
      assert (m_data == s_data[g*8 +: 8]);
      assert (s_ready == (busy ? ({{(NS - 1){1'b0}}, m_ready} << g) : {NS{1'b0}}));
    end
  // The grant moves only between packets.
  always @(posedge clk)
    if (f_past && !$past(rst) && !rst && $past(busy) && busy && $past(g) != g) assert (0);
  always @(posedge clk)
    if (f_past && !$past(rst) && !rst && $past(busy) && $past(!last || !fire)) assert (busy && g == $past(g));

  always @(posedge clk)
    if (f_past && !rst) begin
      cover (fire && last && hidx == 3'd7);                 // a packet with a payload ends
      cover (busy && !s_valid[g] && hidx == 3'd7);          // a source pauses mid-packet
      cover (f_grant_now && pick != g);                     // the grant moves on
    end
`endif
endmodule
`default_nettype wire
