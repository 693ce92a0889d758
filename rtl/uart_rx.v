`default_nettype none
// uart_rx: UART receiver, 8N1, LSB first, idle high.
//
// rx passes a two-flop synchroniser (it is asynchronous to clk). A falling
// edge starts a frame; the start bit is re-checked HALF = CPB/2 clocks later
// (a shorter low glitch is ignored), then every bit is sampled CPB clocks
// after the previous one, i.e. near the middle of each bit, CPB =
// round(CLK_HZ / BAUD) (must be >= 2).
// Latency (exact): if the first posedge that sees rx low is edge 0, m_valid
// is high after edge 2 + HALF + 9 * CPB (2 synchroniser stages, half a bit to
// the start-bit middle, 9 bits to the stop-bit middle). The receiver is
// ready for the next start bit right after the stop-bit sample, so a
// transmitter up to ~(CPB/2 - 1)/ (9.5 CPB) faster still works back to back.
// A stop bit read as 0 is a framing error: frame_err pulses one clock, the
// byte is dropped and the receiver waits for the line to return high.
// Output: valid/ready with a one-byte holding register; a byte completing
// while the previous one is still not taken is dropped (overrun pulses).
module uart_rx #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer BAUD   = 3_000_000
) (
    input  wire       clk,
    input  wire       rst,
    input  wire       rx,
    output reg        m_valid,
    input  wire       m_ready,
    output reg  [7:0] m_data,
    output reg        frame_err,
    output reg        overrun
);
  localparam integer CPB = (CLK_HZ + BAUD / 2) / BAUD;
  // At least 2 clocks per bit (HALF >= 1), and the rounded bit period within
  // 3 % of the baud rate: the stop bit is sampled 9.5 bits after the start
  // edge, so 3 % drifts 0.29 bit and leaves 0.2 bit for sampling jitter.
  generate
    if (BAUD < 1 || CPB < 2 || 100 * (CLK_HZ > CPB * BAUD ? CLK_HZ - CPB * BAUD : CPB * BAUD - CLK_HZ) >
        3 * CPB * BAUD) begin : g_bad_params
      uart_rx_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate
  localparam integer HALF = CPB / 2;
  localparam integer CW = (CPB > 2) ? $clog2(CPB) : 1;
  localparam [CW-1:0] CNT_LAST = CPB[CW-1:0] - 1'b1;
  localparam [CW-1:0] HALF_LAST = HALF[CW-1:0] - 1'b1;

  localparam [2:0] S_IDLE = 3'd0, S_START = 3'd1, S_DATA = 3'd2, S_STOP = 3'd3,
                   S_WAIT = 3'd4;

  reg rx_s1, rx_s2;
  reg [2:0] state;
  reg [CW-1:0] cnt;
  reg [2:0] bitn;
  reg [7:0] shreg;

  always @(posedge clk) begin
    if (rst) begin
      rx_s1 <= 1'b1;
      rx_s2 <= 1'b1;
    end else begin
      rx_s1 <= rx;
      rx_s2 <= rx_s1;
    end
  end

  always @(posedge clk) begin
    frame_err <= 1'b0;
    overrun   <= 1'b0;
    if (m_valid && m_ready) m_valid <= 1'b0;
    if (rst) begin
      state   <= S_IDLE;
      cnt     <= {CW{1'b0}};
      bitn    <= 3'd0;
      shreg   <= 8'd0;
      m_valid <= 1'b0;
      m_data  <= 8'd0;
    end else begin
      case (state)
        S_IDLE:
          if (!rx_s2) begin
            state <= S_START;
            cnt   <= {CW{1'b0}};
          end
        S_START:
          if (cnt == HALF_LAST) begin
            cnt   <= {CW{1'b0}};
            bitn  <= 3'd0;
            state <= rx_s2 ? S_IDLE : S_DATA;
          end else begin
            cnt <= cnt + 1'b1;
          end
        S_DATA:
          if (cnt == CNT_LAST) begin
            cnt   <= {CW{1'b0}};
            shreg <= {rx_s2, shreg[7:1]};
            bitn  <= bitn + 3'd1;
            if (bitn == 3'd7) state <= S_STOP;
          end else begin
            cnt <= cnt + 1'b1;
          end
        S_STOP:
          if (cnt == CNT_LAST) begin
            cnt <= {CW{1'b0}};
            if (!rx_s2) begin
              frame_err <= 1'b1;
              state     <= S_WAIT;
            end else begin
              state <= S_IDLE;
              if (m_valid && !m_ready) begin
                overrun <= 1'b1;
              end else begin
                m_valid <= 1'b1;
                m_data  <= shreg;
              end
            end
          end else begin
            cnt <= cnt + 1'b1;
          end
        default:  // S_WAIT: line must return high before the next start bit
          if (rx_s2) state <= S_IDLE;
      endcase
    end
  end
endmodule
`default_nettype wire
