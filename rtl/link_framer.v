`default_nettype none
// link_framer: packet request in, COBS-framed host-link bytes out (to
// uart_tx). Frame format: docs/protocol.md.
//
//   raw  = type | seq | t (4 bytes LE) | len (2 bytes LE) | payload | crc (2 bytes BE)
//   wire = COBS(raw) | 0x00
//   crc  = CRC-16/CCITT-FALSE over type..payload (rtl/crc16.v).
//   seq  = 8-bit packet counter, +1 per packet (all types share it).
//
// Input: one byte stream carrying whole packets, each as type, t (4 bytes
// LE), len (2 bytes LE), then exactly len payload bytes (the frame engine
// writes them so, through the output FIFO). The framer inserts seq after the
// type and appends the CRC. The header is not held: its bytes go through
// to the encoder as they come (raw order is input order with seq after the
// type), and only len is kept, as the payload count. s_ready is high while
// the encoder can take a byte of the input's (type, t, len, payload).
//
// Structure: an assembler emits the raw bytes (one per clock when the
// encoder can take them) and an end-of-packet marker; the COBS encoder
// collects each block (the non-zero bytes up to the next zero, at most 254)
// in one half of a 512 x 8 RAM (one iCE40 EBR) while the other half is
// being sent, so blocks are ping-ponged and the UART is not starved. Each
// block is sent as its code byte (block length + 1, 0xFF for a full 254-byte
// block) followed by the block; the packet's last block is followed by the
// 0x00 delimiter. The last block is always written, even if empty (code
// 0x01 after a full block at the very end), as host/link/link_encoder does.
// Output: one byte per 2 clocks at best, far above any UART rate (one byte
// per 10 * CPB clocks). m_data is stable while m_valid && !m_ready.
module link_framer (
    input  wire        clk,
    input  wire        rst,
    input  wire        s_valid,
    output wire        s_ready,
    input  wire [7:0]  s_data,
    output reg         m_valid,
    input  wire        m_ready,
    output reg  [7:0]  m_data,
    output reg  [7:0]  seq
);
  // ---------------- assembler: raw bytes + end-of-packet ----------------
  // A_TYPE: the type byte; A_SEQ: seq; A_HDR: t and len (6 bytes, hidx
  // 0..5); then payload, CRC (2 bytes) and the end marker.
  localparam [2:0] A_TYPE = 3'd0, A_SEQ = 3'd1, A_HDR = 3'd2, A_PAY = 3'd3, A_CRC = 3'd4,
                   A_EOP = 3'd5;
  reg [2:0] astate;
  reg [2:0] hidx;        // header byte 0..5 after seq, crc byte 0..1
  reg [15:0] remaining;  // payload bytes left (len, from the header's last two bytes)
  reg [15:0] crc;
  wire [15:0] crc_next;
  wire enc_ready;        // encoder can take a raw byte / the end marker

  wire from_input = (astate == A_TYPE) || (astate == A_HDR) || (astate == A_PAY);
  wire raw_valid = from_input ? s_valid : 1'b1;
  wire raw_eop = (astate == A_EOP);
  wire [7:0] raw_byte = (astate == A_SEQ) ? seq :
                        (astate == A_CRC) ? (hidx[0] ? crc[7:0] : crc[15:8]) : s_data;
  wire raw_take = raw_valid && enc_ready;

  assign s_ready = from_input && enc_ready;

  crc16 u_crc (.crc_in(crc), .data(raw_byte), .crc_out(crc_next));

  always @(posedge clk) begin
    if (rst) begin
      astate    <= A_TYPE;
      hidx      <= 3'd0;
      seq       <= 8'd0;
      crc       <= 16'hFFFF;
      remaining <= 16'd0;
    end else if (raw_take) begin
      if (astate != A_CRC && !raw_eop) crc <= crc_next;  // over type .. payload
      case (astate)
        A_TYPE: astate <= A_SEQ;
        A_SEQ: begin
          hidx   <= 3'd0;
          astate <= A_HDR;
        end
        A_HDR: begin
          hidx <= hidx + 3'd1;
          if (hidx == 3'd4) remaining[7:0] <= s_data;
          if (hidx == 3'd5) begin
            remaining[15:8] <= s_data;
            hidx   <= 3'd0;
            astate <= ({s_data, remaining[7:0]} == 16'd0) ? A_CRC : A_PAY;
          end
        end
        A_PAY: begin
          remaining <= remaining - 16'd1;
          if (remaining == 16'd1) astate <= A_CRC;
        end
        A_CRC: begin
          hidx <= hidx + 3'd1;
          if (hidx[0]) astate <= A_EOP;
        end
        default: begin  // A_EOP
          seq    <= seq + 8'd1;
          crc    <= 16'hFFFF;
          hidx   <= 3'd0;
          astate <= A_TYPE;
        end
      endcase
    end
  end

  // ---------------- COBS encoder: ping-pong block buffer ----------------
  reg [7:0] mem [0:511];
  reg [7:0] rdata;
  reg       wbank, rbank;
  reg [7:0] wcnt;               // bytes in the block being written (0..253)
  reg [1:0] full;               // bank holds a closed block
  reg [7:0] code0, code1;       // code byte of each bank's block
  reg [1:0] last;               // block ends the packet (delimiter follows)
  reg [7:0] ridx;               // next byte of the bank to fetch

  assign enc_ready = !full[wbank];

  wire wr_data = raw_take && !raw_eop && raw_byte != 8'd0;
  wire close = raw_take && (raw_eop || raw_byte == 8'd0 || wcnt == 8'd253);
  wire [7:0] close_code = (raw_take && !raw_eop && raw_byte != 8'd0) ? 8'hFF : wcnt + 8'd1;

  localparam [1:0] R_IDLE = 2'd0, R_OUT = 2'd1, R_FETCH = 2'd2;
  localparam [1:0] K_CODE = 2'd0, K_DATA = 2'd1, K_DELIM = 2'd2;
  reg [1:0] rstate, kind;
  wire [7:0] rcode = rbank ? code1 : code0;
  wire more = ridx != rcode - 8'd1;
  wire release_bank = (rstate == R_OUT) && m_ready &&
                      (kind == K_DELIM || (!more && !last[rbank]));

  always @(posedge clk) begin
    if (wr_data) mem[{wbank, wcnt}] <= raw_byte;
    rdata <= mem[{rbank, ridx}];
  end

  always @(posedge clk) begin
    if (rst) begin
      wbank <= 1'b0;
      wcnt  <= 8'd0;
      full  <= 2'b00;
      last  <= 2'b00;
      code0 <= 8'd0;
      code1 <= 8'd0;
    end else begin
      if (wr_data && !close) wcnt <= wcnt + 8'd1;
      if (close) begin
        full[wbank] <= 1'b1;
        last[wbank] <= raw_eop;
        if (wbank) code1 <= close_code;
        else code0 <= close_code;
        wbank <= ~wbank;
        wcnt  <= 8'd0;
      end
      if (release_bank) full[rbank] <= 1'b0;
    end
  end

  always @(posedge clk) begin
    if (rst) begin
      rstate  <= R_IDLE;
      kind    <= K_CODE;
      rbank   <= 1'b0;
      ridx    <= 8'd0;
      m_valid <= 1'b0;
      m_data  <= 8'd0;
    end else begin
      case (rstate)
        R_IDLE:
          if (full[rbank]) begin
            m_data  <= rcode;
            m_valid <= 1'b1;
            kind    <= K_CODE;
            ridx    <= 8'd0;
            rstate  <= R_OUT;
          end
        R_OUT:
          if (m_ready) begin
            m_valid <= 1'b0;
            if (kind != K_DELIM && more) begin
              rstate <= R_FETCH;          // rdata <= mem[{rbank, ridx}] now
            end else if (kind != K_DELIM && last[rbank]) begin
              m_data  <= 8'd0;
              m_valid <= 1'b1;
              kind    <= K_DELIM;
            end else begin
              rbank  <= ~rbank;
              rstate <= R_IDLE;
            end
          end
        default: begin  // R_FETCH
          m_data  <= rdata;
          m_valid <= 1'b1;
          kind    <= K_DATA;
          ridx    <= ridx + 8'd1;
          rstate  <= R_OUT;
        end
      endcase
    end
  end
`ifdef FORMAL
  // Properties (tests/formal/link_framer.sby). Assumed, of the input only:
  // whole packets (type, t, len, len payload bytes), each byte held until
  // taken; m_ready free; the first clock resets. Proven for every clock:
  // the raw frame handed to the COBS encoder is the protocol's (seq after
  // the type, +1 per packet; the CRC by a bit-serial CRC-16/CCITT-FALSE of
  // its own over type..payload, high byte first; the end of the packet
  // right after it); the output is COBS-shaped (a code byte c, then c - 1
  // non-zero bytes, no 0x00 but the delimiter), exactly one delimiter per
  // packet, and held while not taken. Not proven here: that the encoder's
  // data bytes are the raw bytes in order (a bounded check of that was
  // beyond z3 at a frame's depth); the simulation tests check the framer's
  // output byte for byte against host/link's encoder.
  reg f_past = 1'b0;
  always @(posedge clk) f_past <= 1'b1;
  always @(*) if (!f_past) assume (rst);
  always @(*) if (f_past) assume (!rst);
  always @(posedge clk)
    if (f_past && !$past(rst) && $past(s_valid && !s_ready)) assume (s_valid && s_data == $past(s_data));

  `include "formal_crc16.vh"  // the reference CRC, bit by bit

  // The raw frame, item by item as the encoder takes it: r = 0 type, 1
  // seq, 2..7 t and len, 8.. payload, then the CRC's two bytes and the end.
  reg [16:0] f_r;
  reg [15:0] f_len, f_crc;
  reg [7:0] f_seq, f_lo;
  wire [16:0] f_crc_at = 17'd8 + {1'b0, f_len};  // the CRC's high byte
  always @(posedge clk)
    if (rst) begin
      f_r <= 17'd0;
      f_crc <= 16'hFFFF;
      f_seq <= 8'd0;
    end else if (raw_take) begin
      if (raw_eop) begin
        f_r <= 17'd0;
        f_crc <= 16'hFFFF;
        f_seq <= f_seq + 8'd1;
      end else begin
        f_r <= f_r + 17'd1;
        if (f_r == 17'd6) f_lo <= raw_byte;
        if (f_r == 17'd7) f_len <= {raw_byte, f_lo};
        if (f_r < 17'd8 || f_r < f_crc_at) f_crc <= f_crc16(f_crc, raw_byte);
      end
    end
  always @(*)
    if (f_past && raw_take) begin
      if (f_r == 17'd1) assert (raw_byte == seq && seq == f_seq);
      if (f_r >= 17'd8 && f_r == f_crc_at) assert (raw_byte == f_crc[15:8]);
      if (f_r >= 17'd8 && f_r == f_crc_at + 17'd1) assert (raw_byte == f_crc[7:0]);
      assert (raw_eop == (f_r >= 17'd8 && f_r == f_crc_at + 17'd2));
      if (f_r != 17'd1 && (f_r < 17'd8 || f_r < f_crc_at)) assert (s_ready && raw_byte == s_data);
    end
  // The assembler's state is the raw position (for induction).
  always @(*)
    if (f_past) begin
      assert (crc == f_crc && seq == f_seq);
      assert (astate <= A_EOP);
      if (astate == A_TYPE) assert (f_r == 17'd0);
      if (astate == A_SEQ) assert (f_r == 17'd1);
      if (astate == A_HDR) assert (hidx <= 3'd5 && f_r == 17'd2 + {14'd0, hidx} &&
                                   (hidx == 3'd5 ? remaining[7:0] == f_lo : 1'b1));
      if (astate == A_TYPE) assert (hidx == 3'd0);
      if (astate == A_PAY) assert (hidx == 3'd0 && remaining != 16'd0 && remaining <= f_len &&
                                   f_r == f_crc_at - {1'b0, remaining});
      if (astate == A_CRC) assert (hidx <= 3'd1 && f_r == f_crc_at + {14'd0, hidx});
      if (astate == A_EOP) assert (f_r == f_crc_at + 17'd2);
    end

  // The output, as the host's COBS decoder reads it.
  reg f_incode;        // a code byte (or the delimiter) is due
  reg [7:0] f_left;    // data bytes left in the block
  reg [15:0] f_neop, f_ndel;  // ends of packets taken, delimiters sent
  wire f_fire = m_valid && m_ready;
  always @(posedge clk)
    if (rst) begin
      f_incode <= 1'b1;
      f_left <= 8'd0;
      f_neop <= 16'd0;
      f_ndel <= 16'd0;
    end else begin
      if (raw_take && raw_eop) f_neop <= f_neop + 16'd1;
      if (f_fire) begin
        if (f_incode && m_data == 8'd0) f_ndel <= f_ndel + 16'd1;  // a 0x00 elsewhere is checked below
        else if (f_incode) begin
          f_left <= m_data - 8'd1;
          f_incode <= m_data == 8'd1;
        end else begin
          f_left <= f_left - 8'd1;
          f_incode <= f_left == 8'd1;
        end
      end
    end
  // Bytes in the buffer are never 0 (any address f_a of either bank).
  (* anyconst *) reg [7:0] f_a;
  wire [1:0] f_pend = {1'b0, full[0] && last[0]} + {1'b0, full[1] && last[1]};
  always @(*)
    if (f_past) begin
      // No 0x00 inside a block: code bytes by their invariant, data bytes
      // at any address f_a (so at every address).
      if (f_fire && m_data == 8'd0 && (kind != K_DATA || ridx - 8'd1 == f_a)) assert (f_incode);
      assert (m_valid == (rstate == R_OUT));
      assert (rstate != 2'd3 && kind != 2'd3);
      // One delimiter per packet: the ends taken, less the delimiters
      // sent, are the closed blocks that end a packet.
      assert (f_neop - f_ndel == {14'd0, f_pend});
      // The code bytes: a bank's code counts its bytes (1..255); the
      // decoder's count of data bytes left is the bank's.
      if (full[0]) assert (code0 != 8'd0);
      if (full[1]) assert (code1 != 8'd0);
      assert (wcnt <= 8'd253 && (full[wbank] ? wcnt == 8'd0 : 1'b1));
      if (f_a < wcnt && !full[wbank]) assert (mem[{wbank, f_a}] != 8'd0);
      if (full[0] && {1'b0, f_a} + 9'd1 < {1'b0, code0}) assert (mem[{1'b0, f_a}] != 8'd0);
      if (full[1] && {1'b0, f_a} + 9'd1 < {1'b0, code1}) assert (mem[{1'b1, f_a}] != 8'd0);
      if (rstate == R_IDLE) assert (f_incode);
      if (rstate != R_IDLE) assert (full[rbank]);
      if (rstate == R_FETCH) assert (!f_incode && ridx < rcode - 8'd1 && f_left == rcode - 8'd1 - ridx);
      if (rstate == R_FETCH && ridx == f_a) assert (rdata == mem[{rbank, ridx}] && rdata != 8'd0);
      if (rstate == R_OUT && kind == K_CODE) assert (f_incode && m_data == rcode && ridx == 8'd0);
      if (rstate == R_OUT && kind == K_DATA) assert (!f_incode && ridx != 8'd0 && ridx <= rcode - 8'd1 &&
                                                     f_left == rcode - ridx);
      if (rstate == R_OUT && kind == K_DATA && ridx - 8'd1 == f_a) assert (m_data != 8'd0);
      if (rstate == R_OUT && kind == K_DELIM) assert (f_incode && m_data == 8'd0 && last[rbank]);
    end
  always @(posedge clk)
    if (f_past && !$past(rst) && $past(m_valid && !m_ready)) assert (m_valid && m_data == $past(m_data));

`ifndef FORMAL_COVER_FRAME
  always @(posedge clk)
    if (f_past) begin
      cover (raw_take && raw_eop && f_len != 16'd0);         // a packet with a payload taken whole
      cover (f_fire && !f_incode);                          // a data byte out
      cover (m_valid && !m_ready && !f_incode);             // a stall mid-block
      cover (full == 2'b11);                                // both banks closed
    end
`endif
`ifdef FORMAL_COVER_FRAME
  // The cover_frame task only: a narrowed input (always valid, len 0,
  // always ready) so that a whole frame ends within the solver's reach.
  always @(*) begin
    assume (s_valid && m_ready);
    if (f_r == 17'd6 || f_r == 17'd7) assume (s_data == 8'd0);
  end
  always @(posedge clk) if (f_past) cover (f_fire && f_incode && m_data == 8'd0);  // a frame ends
`endif
`endif
endmodule
`default_nettype wire
