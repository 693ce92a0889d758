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
endmodule
`default_nettype wire
