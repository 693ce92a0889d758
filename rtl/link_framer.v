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
// type and appends the CRC. s_ready is high while it collects the 7 header
// bytes and while it takes payload bytes.
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
  localparam [2:0] A_IDLE = 3'd0, A_HDR = 3'd1, A_PAY = 3'd2, A_CRC = 3'd3, A_EOP = 3'd4;
  reg [2:0] astate;
  reg [2:0] aidx;        // header byte 0..7, crc byte 0..1
  reg [7:0] typ;
  reg [31:0] tstamp;
  reg [15:0] len, remaining;
  reg [15:0] crc;
  wire [15:0] crc_next;
  wire enc_ready;        // encoder can take a raw byte / the end marker

  reg [7:0] hdr_byte;
  always @(*) begin
    case (aidx)
      3'd0: hdr_byte = typ;
      3'd1: hdr_byte = seq;
      3'd2: hdr_byte = tstamp[7:0];
      3'd3: hdr_byte = tstamp[15:8];
      3'd4: hdr_byte = tstamp[23:16];
      3'd5: hdr_byte = tstamp[31:24];
      3'd6: hdr_byte = len[7:0];
      default: hdr_byte = len[15:8];
    endcase
  end

  wire raw_valid = (astate == A_HDR) || (astate == A_CRC) || (astate == A_EOP) ||
                   (astate == A_PAY && s_valid);
  wire raw_eop = (astate == A_EOP);
  wire [7:0] raw_byte = (astate == A_PAY) ? s_data :
                        (astate == A_CRC) ? (aidx[0] ? crc[7:0] : crc[15:8]) : hdr_byte;
  wire raw_take = raw_valid && enc_ready;

  assign s_ready = (astate == A_IDLE) || ((astate == A_PAY) && enc_ready);

  crc16 u_crc (.crc_in(crc), .data(raw_byte), .crc_out(crc_next));

  always @(posedge clk) begin
    if (rst) begin
      astate    <= A_IDLE;
      aidx      <= 3'd0;
      seq       <= 8'd0;
      crc       <= 16'hFFFF;
      typ       <= 8'd0;
      tstamp    <= 32'd0;
      len       <= 16'd0;
      remaining <= 16'd0;
    end else begin
      case (astate)
        A_IDLE:  // collect type, t, len from the stream
          if (s_valid) begin
            case (aidx)
              3'd0: typ <= s_data;
              3'd1: tstamp[7:0] <= s_data;
              3'd2: tstamp[15:8] <= s_data;
              3'd3: tstamp[23:16] <= s_data;
              3'd4: tstamp[31:24] <= s_data;
              3'd5: len[7:0] <= s_data;
              default: len[15:8] <= s_data;
            endcase
            aidx <= aidx + 3'd1;
            if (aidx == 3'd6) begin
              remaining <= {s_data, len[7:0]};
              crc       <= 16'hFFFF;
              aidx      <= 3'd0;
              astate    <= A_HDR;
            end
          end
        A_HDR:
          if (raw_take) begin
            crc  <= crc_next;
            aidx <= aidx + 3'd1;
            if (aidx == 3'd7) begin
              aidx   <= 3'd0;
              astate <= (remaining == 16'd0) ? A_CRC : A_PAY;
            end
          end
        A_PAY:
          if (raw_take) begin
            crc       <= crc_next;
            remaining <= remaining - 16'd1;
            if (remaining == 16'd1) astate <= A_CRC;
          end
        A_CRC:
          if (raw_take) begin
            aidx <= aidx + 3'd1;
            if (aidx[0]) astate <= A_EOP;
          end
        default:  // A_EOP
          if (raw_take) begin
            seq    <= seq + 8'd1;
            aidx   <= 3'd0;
            astate <= A_IDLE;
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
