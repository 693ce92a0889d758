`default_nettype none
// adc_ad7476: SPI master for NCH AD7476A ADCs sharing CS and SCLK (the
// Digilent Pmod AD1 has two), 12-bit sample stream out.
//
// Conversion timing, in clocks of clk (H = SCLK_DIV, E0 = edge that drops CS):
//   CS falls at E0; SCLK (idle high) falls at E0 + (2k-1) H and rises at
//   E0 + 2k H for k = 1..16; CS rises with the 16th rising edge (E0 + 32 H).
//   Conversions start every PERIOD = round(CLK_HZ / SAMPLE_HZ) clocks while
//   en is high (the actual rate is CLK_HZ / PERIOD).
//   f_SCLK = CLK_HZ / (2 H). Datasheet limits the parameters must meet (the
//   model sim/ad7476_model.h checks them): f_SCLK <= 20 MHz; t2 = H clocks
//   >= 10 ns; tQUIET: (PERIOD - 31 H) clocks >= 36 ns (t8 max) + 50 ns;
//   tACQ: (PERIOD - 28 H) clocks >= 250 ns. 12 MHz, H = 1 (6 MHz SCLK),
//   35 kSPS (PERIOD 343) and 40 MHz, H = 1 (20 MHz), 1 MSPS (PERIOD 40) both
//   meet them.
// Sampling choice: SDATA bit k is registered on the clock edge that drives
//   the k-th SCLK falling edge (bit 1 is the first leading zero, put out by
//   CS falling; bit 16 is DB0). That edge sees the bit the ADC put out one
//   SCLK period earlier, so the setup budget is a full tSCLK - t4 (40 ns max
//   access time; 10 ns at 20 MHz, 127 ns at 6 MHz) and the hold budget is
//   t7 (>= 10 ns) plus the FPGA's own clock-to-SCLK-pin delay, which only
//   helps. Sampling on the rising edge instead would leave tSCLK/2 - t4,
//   negative at 20 MHz. SDATA is source-synchronous to our own SCLK, so it
//   is not passed through a synchroniser (that would shift the sample point).
// Output stream: one token per conversion, m_data = {ch NCH-1, ..., ch 0}
//   12 bits each (unsigned codes), m_t = conversion index (32-bit sample
//   counter, counts every conversion started). m_valid rises 31 H clocks
//   after E0 (registered on the edge that drives the 16th SCLK fall). If the previous token
//   has not been taken by then, the new one is dropped and `overruns`
//   (saturating 16 bits) counts it; m_t then shows the gap.
module adc_ad7476 #(
    parameter integer CLK_HZ    = 12_000_000,
    parameter integer SAMPLE_HZ = 35_000,
    parameter integer SCLK_DIV  = 1,  // clocks per SCLK half period (H >= 1)
    parameter integer NCH       = 1
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              en,
    output reg               cs_n,
    output reg               sclk,
    input  wire [NCH-1:0]    sdata,
    output reg               m_valid,
    input  wire              m_ready,
    output reg  [12*NCH-1:0] m_data,
    output reg  [31:0]       m_t,
    output reg  [15:0]       overruns,
    input  wire              clear       // zero `overruns` (CLEAR_COUNTERS)
);
  localparam integer PERIOD = (CLK_HZ + SAMPLE_HZ / 2) / SAMPLE_HZ;
  // The AD7476A's limits (header): f_SCLK = CLK_HZ / (2 H) <= 20 MHz,
  // t2 = H clocks >= 10 ns, tQUIET = (PERIOD - 31 H) clocks >= 86 ns and
  // tACQ = (PERIOD - 28 H) clocks >= 250 ns (ceil(CLK_HZ * t) clocks; kHz
  // and the clock counts clamped at 2000, which is more than 250 ns below
  // 8 GHz, keep the products in 32 bits: unclamped, 80 MHz at 35 kS/s,
  // PERIOD 2286, overflowed and was refused).
  localparam integer CLK_KHZ = CLK_HZ / 1000;
  localparam integer QUIET = PERIOD - 31 * SCLK_DIV > 2000 ? 2000 : PERIOD - 31 * SCLK_DIV;
  localparam integer ACQ = PERIOD - 28 * SCLK_DIV > 2000 ? 2000 : PERIOD - 28 * SCLK_DIV;
  generate
    if (NCH < 1 || SCLK_DIV < 1 || SAMPLE_HZ < 1 || CLK_HZ > 40_000_000 * SCLK_DIV ||
        SCLK_DIV * 100_000 < CLK_KHZ || QUIET * 1_000_000 < CLK_KHZ * 86 ||
        ACQ * 1_000_000 < CLK_KHZ * 250) begin : g_bad_params
      adc_ad7476_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate
  localparam integer PW = $clog2(PERIOD);
  localparam integer HW = (SCLK_DIV > 1) ? $clog2(SCLK_DIV) : 1;
  localparam [PW-1:0] P_LAST = PERIOD[PW-1:0] - 1'b1;
  localparam [HW-1:0] H_LAST = SCLK_DIV[HW-1:0] - 1'b1;

  reg [PW-1:0] pcnt;          // position in the sample period
  reg busy;                   // CS low
  reg [HW-1:0] hcnt;          // clocks into the current SCLK half period
  reg [4:0] half;             // half periods done: even -> next edge falls
  reg [16*NCH-1:0] shreg;
  reg [31:0] count;           // conversions completed: the next one's index

  // Shift register after this falling edge's sample (bits 15..0 per channel).
  reg [16*NCH-1:0] shifted;
  integer c;
  always @(*) begin
    for (c = 0; c < NCH; c = c + 1)
      shifted[16*c +: 16] = {shreg[16*c +: 15], sdata[c]};
  end

  // The 12 data bits of each channel once all 16 are in.
  reg [12*NCH-1:0] codes;
  integer d;
  always @(*) begin
    for (d = 0; d < NCH; d = d + 1)
      codes[12*d +: 12] = shifted[16*d +: 12];
  end

  always @(posedge clk) begin
    if (rst) begin
      pcnt     <= {PW{1'b0}};
      busy     <= 1'b0;
      cs_n     <= 1'b1;
      sclk     <= 1'b1;
      hcnt     <= {HW{1'b0}};
      half     <= 5'd0;
      shreg    <= {16*NCH{1'b0}};
      count    <= 32'd0;
      m_valid  <= 1'b0;
      m_data   <= {12*NCH{1'b0}};
      m_t      <= 32'd0;
      overruns <= 16'd0;
    end else begin
      if (clear) overruns <= 16'd0;
      if (m_valid && m_ready) m_valid <= 1'b0;
      pcnt <= (pcnt == P_LAST) ? {PW{1'b0}} : pcnt + 1'b1;

      if (!busy) begin
        if (pcnt == {PW{1'b0}} && en) begin
          busy  <= 1'b1;
          cs_n  <= 1'b0;
          hcnt  <= {HW{1'b0}};
          half  <= 5'd0;
        end
      end else if (hcnt != H_LAST) begin
        hcnt <= hcnt + 1'b1;
      end else begin
        hcnt <= {HW{1'b0}};
        half <= half + 5'd1;
        if (!half[0]) begin
          // SCLK falling edge k = half/2 + 1: take bit k.
          sclk  <= 1'b0;
          shreg <= shifted;
          if (half == 5'd30) begin  // 16th falling edge: sample complete
            // Its index: every conversion started completes (only rst
            // stops one), in order, so the completed ones before it are
            // the started ones before it, lost samples included.
            count <= count + 32'd1;
            if (m_valid && !m_ready) begin
              if (overruns != 16'hFFFF && !clear) overruns <= overruns + 16'd1;
            end else begin
              m_valid <= 1'b1;
              m_data  <= codes;
              m_t     <= count;
            end
          end
        end else begin
          sclk <= 1'b1;
          if (half == 5'd31) begin  // 16th rising edge: end of conversion
            cs_n <= 1'b1;
            busy <= 1'b0;
          end
        end
      end
    end
  end
endmodule
`default_nettype wire
