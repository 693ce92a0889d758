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
//   model sim/ad7476_model.h checks them): 10 kHz <= f_SCLK <= 20 MHz;
//   t2 = H clocks >= 10 ns; tQUIET: (PERIOD - 31 H) clocks >= 36 ns (t8
//   max) + 50 ns; tACQ: (PERIOD - 28 H) clocks >= 250 ns; t1: (PERIOD -
//   32 H) clocks >= 10 ns. 12 MHz, H = 1 (6 MHz SCLK),
//   35 kSPS (PERIOD 343) and 40 MHz, H = 1 (20 MHz), 1 MSPS (PERIOD 40) both
//   meet them.
// Sampling choice: bit k of SDATA (bit 1 is the first leading zero, put out
//   by CS falling; bit 16 is DB0) is valid at our capture flip-flop from
//   RT + t4 after the edge that drove SCLK fall k - 1 until RT + t7 after the
//   edge that drives fall k, RT the round trip of SCLK out and SDATA back
//   (clock to out, pads, board: SDATA_RT_MIN_NS .. SDATA_RT_MAX_NS, the
//   range sim/ad7476_model.h's Ad7476Board tests). Relative to the edge
//   that drives fall k the window is [RT_MAX + 40 ns - tSCLK, RT_MIN +
//   10 ns]: at 20 MHz SCLK [RT_MAX - 10, RT_MIN + 10] ns, so that edge
//   itself (0) is outside it once the round trip passes 10 ns, which any
//   real pads do. The capture is LAG half clocks after that edge, the first
//   0 (that edge: every build with tSCLK - t4 well above the round trip)
//   if it leaves SDATA_MARGIN_PS on both sides of the window, else the
//   roomier of 1 (the falling clock edge after it: 40 MHz, H = 1) and 2
//   (the next rising edge: 80 MHz, H = 2) if it does; elaboration stops
//   when none does. With LAG > 0 the
//   bit enters the shift register and the code the output one clock after
//   the edge that drives the fall. SDATA is source-synchronous to our own
//   SCLK, so it is not passed through a synchroniser (that would shift the
//   sample point). nextpnr (0.11) takes no input or output delay
//   constraints, so the round trip is this module's parameters, not the
//   tool's check: docs/protocol.md section 1.
// Output stream: one token per conversion, m_data = {ch NCH-1, ..., ch 0}
//   12 bits each (unsigned codes), m_t = conversion index (32-bit sample
//   counter, counts every conversion started). m_valid rises 31 H clocks
//   after E0 (registered on the edge that drives the 16th SCLK fall), a
//   clock later when LAG > 0. If the previous token
//   has not been taken by then, the new one is dropped and `overruns`
//   (saturating 16 bits) counts it; m_t then shows the gap.
module adc_ad7476 #(
    parameter integer CLK_HZ    = 12_000_000,
    parameter integer SAMPLE_HZ = 35_000,
    parameter integer SCLK_DIV  = 1,  // clocks per SCLK half period (H >= 1)
    parameter integer NCH       = 1,
    // The round trip SCLK out, SDATA back (header), ns, and the least room
    // the sample point must leave on each side of SDATA's valid window.
    parameter integer SDATA_RT_MIN_NS = 5,
    parameter integer SDATA_RT_MAX_NS = 15,
    parameter integer SDATA_MARGIN_PS = 1000
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
  // t1 (CS high) = (PERIOD - 32 H) clocks >= 10 ns: with CS still low at the
  // period's start the conversion would be skipped (half the rate).
  localparam integer T1 = PERIOD - 32 * SCLK_DIV > 2000 ? 2000 : PERIOD - 32 * SCLK_DIV;
  // The sample point (header): SDATA's window around the edge that drives
  // an SCLK fall, in ps (the clock period from kHz: 40 MHz is exact), and
  // the room a capture d ps after that edge leaves on its tighter side.
  localparam integer T_PS = 1_000_000_000 / (CLK_KHZ < 1 ? 1 : CLK_KHZ);
  localparam integer W_LO = SDATA_RT_MAX_NS * 1000 + 40_000 - 2 * SCLK_DIV * T_PS;
  localparam integer W_HI = SDATA_RT_MIN_NS * 1000 + 10_000;
  function integer room(input integer d);
    room = (d - W_LO < W_HI - d) ? d - W_LO : W_HI - d;
  endfunction
  localparam integer LAG = room(0) >= SDATA_MARGIN_PS ? 0
                         : room(T_PS / 2) >= SDATA_MARGIN_PS && room(T_PS / 2) >= room(T_PS) ? 1
                         : room(T_PS) >= SDATA_MARGIN_PS ? 2 : 3;
  generate
    if (NCH < 1 || SCLK_DIV < 1 || SAMPLE_HZ < 1 || CLK_HZ > 40_000_000 * SCLK_DIV ||
        LAG > 2 || SDATA_RT_MIN_NS < 0 || SDATA_RT_MAX_NS < SDATA_RT_MIN_NS ||
        CLK_HZ < 20_000 * SCLK_DIV ||  // f_SCLK >= 10 kHz
        SCLK_DIV * 100_000 < CLK_KHZ || QUIET * 1_000_000 < CLK_KHZ * 86 ||
        ACQ * 1_000_000 < CLK_KHZ * 250 ||
        T1 < 1 || T1 * 1_000_000 < CLK_KHZ * 10) begin : g_bad_params
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

  // SDATA at the sample point: LAG 1 registers it on the falling clock edge
  // (the rising edge after takes it), 0 and 2 take it as it is at a rising
  // edge.
  wire [NCH-1:0] sd_at;
  generate
    if (LAG == 1) begin : g_neg
      reg [NCH-1:0] sd_neg;
`ifdef FORMAL
      // The proof has one clock (sby without multiclock), whose steps hold
      // the free input sdata constant: a register on either edge of a step
      // takes the same value, so the rising edge stands for the falling
      // one (which yosys would refuse beside rising-edge registers).
      always @(posedge clk) sd_neg <= sdata;
`else
      always @(negedge clk) sd_neg <= sdata;
`endif
      assign sd_at = sd_neg;
    end else begin : g_pos
      assign sd_at = sdata;
    end
  endgenerate

  // This edge drives an SCLK fall (the 16th); the last edge did (LAG > 0
  // takes the bit then).
  wire fall_now = busy && hcnt == H_LAST && !half[0];
  wire last_now = fall_now && half == 5'd30;
  reg fall_q, last_q;
  wire take = LAG == 0 ? fall_now : fall_q;
  wire take16 = LAG == 0 ? last_now : last_q;

  // Shift register after this sample (bits 15..0 per channel).
  reg [16*NCH-1:0] shifted;
  integer c;
  always @(*) begin
    for (c = 0; c < NCH; c = c + 1)
      shifted[16*c +: 16] = {shreg[16*c +: 15], sd_at[c]};
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
      fall_q   <= 1'b0;
      last_q   <= 1'b0;
    end else begin
      if (clear) overruns <= 16'd0;
      if (m_valid && m_ready) m_valid <= 1'b0;
      pcnt <= (pcnt == P_LAST) ? {PW{1'b0}} : pcnt + 1'b1;
      fall_q <= fall_now;
      last_q <= last_now;
      if (take) shreg <= shifted;
      if (take16) begin  // the 16th bit is in: sample complete
        // Its index: every conversion started completes (only rst stops
        // one), in order, so the completed ones before it are the started
        // ones before it, lost samples included.
        count <= count + 32'd1;
        if (m_valid && !m_ready) begin
          if (overruns != 16'hFFFF && !clear) overruns <= overruns + 16'd1;
        end else begin
          m_valid <= 1'b1;
          m_data  <= codes;
          m_t     <= count;
        end
      end

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
          sclk <= 1'b0;  // SCLK falling edge k = half/2 + 1 (bit k: take, above)
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
`ifdef FORMAL
  // Properties (tests/formal/adc_ad7476.sby). Inputs free (en, sdata,
  // m_ready, clear); the first clock resets. The monitor keeps the
  // schedule of docs/protocol.md §1 with its own counters: conversions
  // start (CS falls) only PERIOD clocks apart; then SCLK falls at
  // E0 + (2k-1)H and rises at E0 + 2kH, k = 1..16, and CS rises with the
  // 16th rise. The pins must follow it exactly, which makes t2 (CS to
  // SCLK) H clocks, t5/t6 (SCLK low/high) H clocks each, 16 clocks per
  // conversion, t1 (CS high) and tQUIET at least PERIOD - 32H and
  // PERIOD - 31H clocks: the clock counts the elaboration check holds to
  // the datasheet's nanoseconds. And the code delivered is the 12 bits
  // SDATA showed at the sample points of SCLK falls 5..16: the edges that
  // drive them (LAG 0), the clocks after (LAG 2). The proof has one clock
  // (sby without multiclock): LAG 1's falling-edge register is a register
  // of that clock (g_neg), so its sample is SDATA as the step of the edge
  // that drives the fall shows it, taken a clock later as with LAG 2; what
  // the half clock buys in time is the pin model's to show (tests/rtl).
  reg f_past = 1'b0;
  always @(posedge clk) f_past <= 1'b1;
  always @(*) if (!f_past) assume (rst);
  always @(*) if (f_past) assume (!rst);

  localparam [15:0] F_H = SCLK_DIV, F_PERIOD = PERIOD;
  reg [15:0] f_pc;     // clocks into the sample period (conversions start at 0)
  reg f_conv;          // CS should be low
  reg [15:0] f_h;      // clocks into the SCLK half period
  reg [5:0] f_half;    // half periods done
  reg [15:0] f_sh;     // SDATA at each scheduled SCLK fall
  reg [15:0] f_gap;    // clocks since CS rose (saturating)
  wire f_fall = f_conv && f_h == F_H - 16'd1 && !f_half[0];
  wire f_rise = f_conv && f_h == F_H - 16'd1 && f_half[0];
  reg f_got16, f_full;  // the 16th bit was taken at the last edge; the output was full then
  reg f_fall_q, f_last_q, f_sd_q;  // the last edge drove a fall (the 16th); SDATA then
  wire f_take = LAG == 0 ? f_fall : f_fall_q;
  wire f_take16 = LAG == 0 ? f_fall && f_half == 6'd30 : f_last_q;
  wire f_bit = LAG == 1 ? f_sd_q : sdata[0];
  always @(posedge clk) f_sd_q <= sdata[0];  // as g_neg's register: reset or not
  always @(posedge clk)
    if (rst) begin
      f_pc <= 16'd0;
      f_conv <= 1'b0;
      f_h <= 16'd0;
      f_half <= 6'd0;
      f_sh <= 16'd0;
      f_gap <= 16'hFFFF;
      f_got16 <= 1'b0;
      f_fall_q <= 1'b0;
      f_last_q <= 1'b0;
    end else begin
      f_pc <= (f_pc == F_PERIOD - 16'd1) ? 16'd0 : f_pc + 16'd1;
      f_got16 <= f_take16;
      f_full <= m_valid && !m_ready;
      f_fall_q <= f_fall;
      f_last_q <= f_fall && f_half == 6'd30;
      if (f_take) f_sh <= {f_sh[14:0], f_bit};
      if (!f_conv) begin
        if (f_gap != 16'hFFFF) f_gap <= f_gap + 16'd1;
        if (f_pc == 16'd0 && en) begin
          f_conv <= 1'b1;
          f_h <= 16'd0;
          f_half <= 6'd0;
        end
      end else if (f_h != F_H - 16'd1) f_h <= f_h + 16'd1;
      else begin
        f_h <= 16'd0;
        f_half <= f_half + 6'd1;
        if (f_rise && f_half == 6'd31) begin
          f_conv <= 1'b0;
          f_gap <= 16'd0;
        end
      end
    end
  always @(*)
    if (f_past) begin
      assert (cs_n == !f_conv);                           // CS: the schedule's
      assert (sclk == (!f_conv || !f_half[0]));           // SCLK: idle high, H clocks per level
      if (f_conv) assert (f_half <= 6'd31);               // 16 SCLK cycles per conversion
      // t1 / tQUIET: CS high at least PERIOD - 32H clocks before it falls.
      if (!cs_n && f_conv && f_half == 6'd0 && f_h == 16'd0 && f_gap != 16'hFFFF)
        assert (f_gap + 16'd1 >= F_PERIOD - 16'd32 * F_H);
      // The code: bits 5..16 of the last conversion, unless the token
      // before it was still waiting (then overruns counts it).
      // (LAG > 0: the RTL's strobes are the monitor's, a clock on.)
      assert (fall_q == f_fall_q && last_q == f_last_q);
      if (LAG == 1) assert (sd_at[0] == f_sd_q);  // the falling-edge register
      if (f_got16 && !f_full) assert (m_valid && m_data[11:0] == f_sh[11:0]);
      // The state, for induction: the counters are the monitor's.
      assert ({{(16 - PW){1'b0}}, pcnt} == f_pc && f_pc < F_PERIOD);
      assert (busy == f_conv);
      if (f_conv) assert ({{(16 - HW){1'b0}}, hcnt} == f_h && f_h < F_H && {1'b0, half} == f_half);
      assert (shreg[15:0] == f_sh);
      if (f_conv) assert (f_pc == {10'd0, f_half} * F_H + f_h + 16'd1);
      if (f_conv && f_gap != 16'hFFFF) assert (f_gap + 16'd1 >= F_PERIOD - 16'd32 * F_H);
      if (!f_conv && f_gap < F_PERIOD)
        assert (f_pc == ((16'd32 * F_H + 16'd1 + f_gap >= F_PERIOD) ? 16'd32 * F_H + 16'd1 + f_gap - F_PERIOD
                                                                   : 16'd32 * F_H + 16'd1 + f_gap));
    end

  // The datasheet at the pins (AD7476A Table 4, docs/protocol.md §1), with
  // counters of this monitor's own that see only cs_n, sclk, sdata, en and
  // the output stream. Each time is a count of clocks between two pin
  // edges; each limit is the datasheet's time in clocks, rounded up from
  // CLK_HZ rounded up to kHz (so never shorter than the datasheet's):
  // t1 CS high >= 10 ns, t2 CS to SCLK >= 10 ns, tSCLK 50 ns .. 100 us
  // (fSCLK 20 MHz .. 10 kHz; the slow limit rounded down), SDATA sampled
  // no sooner than t3 (22 ns) after CS fell and t4 (40 ns) after the
  // SCLK fall that put the bit out, t5/t6 SCLK
  // low/high >= 0.4 tSCLK (of the period they are part of), tQUIET: 16th
  // SCLK fall + t8 (36 ns max) + 50 ns before CS falls, tACQ: 13th SCLK
  // fall >= 250 ns before CS falls; 16 SCLK cycles per CS low; CS falls
  // PERIOD clocks apart, and exactly PERIOD while en stays high.
  localparam integer F_KHZ = (CLK_HZ + 999) / 1000;
  function integer f_ns(input integer ns);
    f_ns = (F_KHZ * ns + 999_999) / 1_000_000;
  endfunction
  localparam [23:0] F_SAT = 24'hFFFFFF;
  localparam [23:0] F_T1 = f_ns(10), F_T2 = f_ns(10), F_QUIET = f_ns(36 + 50),
                    F_ACQ = f_ns(250), F_TSCLK_MIN = f_ns(50), F_TSCLK_MAX = CLK_HZ / 10_000,
                    F_PER = PERIOD, F_T3 = f_ns(22), F_T4 = f_ns(40);
  reg p_cs, p_sclk;                  // the pins one clock ago
  reg [23:0] p_csf, p_csr, p_fall, p_rise, p_13, p_16, p_hi;
  reg [4:0] p_nf, p_nr;              // SCLK falls / rises since CS fell
  reg p_en;                          // en high at every edge since CS fell
  reg [NCH-1:0] p_sd;                // SDATA at the last edge
  reg [16*NCH-1:0] p_sh;             // SDATA at the edges that drove SCLK falls
  reg p_full;                        // the output held an untaken token
  reg [12*NCH-1:0] p_md;             // m_data one clock ago
  wire e_csf = p_cs && !cs_n, e_csr = !p_cs && cs_n;
  wire e_fall = p_sclk && !sclk, e_rise = !p_sclk && sclk;
  reg p_16q;                         // the 16th fall was seen one clock ago
  wire p_done = LAG == 0 ? e_fall && p_nf == 5'd15 : p_16q;  // its code is out now
  reg [12*NCH-1:0] p_codes_q;        // the codes then
  reg [16*NCH-1:0] p_shn;
  integer g;
  // SDATA at the sample point of the fall seen now: at the edge that drove
  // it (LAG 0, 1: see above) or now (LAG 2).
  wire [NCH-1:0] p_bit = LAG == 2 ? sdata : p_sd;
  always @(*)
    for (g = 0; g < NCH; g = g + 1) p_shn[16*g +: 16] = {p_sh[16*g +: 15], p_bit[g]};
  function [23:0] f_inc(input [23:0] x);
    f_inc = (x == F_SAT) ? F_SAT : x + 24'd1;
  endfunction
  always @(posedge clk)
    if (rst) begin
      p_cs <= 1'b1;
      p_sclk <= 1'b1;
      {p_csf, p_csr, p_fall, p_rise, p_13, p_16, p_hi} <= {7{F_SAT}};
      p_nf <= 5'd0;
      p_nr <= 5'd0;
      p_en <= 1'b0;
      p_sh <= {16*NCH{1'b0}};
      p_full <= 1'b0;
      p_16q <= 1'b0;
    end else begin
      p_16q <= e_fall && p_nf == 5'd15;
      p_codes_q <= p_codes;
      p_cs <= cs_n;
      p_sclk <= sclk;
      p_sd <= sdata;
      p_full <= m_valid && !m_ready;
      p_md <= m_data;
      p_csf <= e_csf ? 24'd1 : f_inc(p_csf);
      p_csr <= e_csr ? 24'd1 : f_inc(p_csr);
      p_fall <= e_fall ? 24'd1 : f_inc(p_fall);
      p_rise <= e_rise ? 24'd1 : f_inc(p_rise);
      p_13 <= (e_fall && p_nf == 5'd12) ? 24'd1 : f_inc(p_13);
      p_16 <= (e_fall && p_nf == 5'd15) ? 24'd1 : f_inc(p_16);
      p_en <= (e_csf || p_en) && en;
      if (e_csf) begin
        p_nf <= 5'd0;
        p_nr <= 5'd0;
      end
      if (e_fall) begin
        p_nf <= p_nf + 5'd1;
        p_hi <= p_rise;
        p_sh <= p_shn;
      end
      if (e_rise) p_nr <= p_nr + 5'd1;
    end
  always @(*)
    if (f_past) begin
      if (cs_n) assert (sclk);                          // SCLK idles high with CS
      if (e_csf) begin
        assert (p_csr >= F_T1);                         // t1
        assert (p_16 >= F_QUIET);                       // tQUIET (+ t8)
        assert (p_13 >= F_ACQ);                         // tACQ
        assert (p_csf >= F_PER);                        // the sample period
      end
      // en high at every edge since CS fell: CS falls again PERIOD clocks on.
      assert (!(p_en && cs_n && p_csf >= F_PER));
      if (e_fall) begin
        assert (!cs_n && p_nf <= 5'd15);
        // The sampling instants (SDATA is registered on the clock edge that
        // drives this fall): bit 1 was put out by CS falling at most t3
        // (22 ns) before, every later bit by the previous fall at most t4
        // (40 ns) before (pin delays aside: docs/protocol.md).
        if (p_nf == 5'd0) assert (p_csf >= F_T2 && p_csf >= F_T3);  // t2, t3
        else begin
          assert (p_fall >= F_T4);                       // t4
          assert (p_fall >= F_TSCLK_MIN && p_fall <= F_TSCLK_MAX);  // fSCLK
          assert (24'd10 * p_rise >= 24'd4 * p_fall);   // t6
        end
      end
      if (e_rise) begin
        assert (p_nf >= 5'd1 && p_nr <= 5'd15);
        if (p_nf >= 5'd2) assert (24'd10 * p_fall >= 24'd4 * (p_fall + p_hi));  // t5
        if (p_nr >= 5'd1) assert (p_rise >= F_TSCLK_MIN && p_rise <= F_TSCLK_MAX);
      end
      if (e_csr) assert (e_rise && p_nf == 5'd16 && p_nr == 5'd15);  // 16 SCLK cycles
      // The code: the 16th fall delivers bits 5..16 (DB11 first) of every
      // channel, or, with the last token still waiting, keeps it and counts
      // (LAG > 0: a clock later).
      if (p_done) begin
        if (!p_full) assert (m_valid && m_data == (LAG == 0 ? p_codes : p_codes_q));
        else assert (m_valid && m_data == p_md);
      end
    end
  reg [12*NCH-1:0] p_codes;
  integer h;
  always @(*)
    for (h = 0; h < NCH; h = h + 1) p_codes[12*h +: 12] = p_shn[16*h +: 12];
  // For induction only: the pin monitor's counters against the schedule's
  // (the schedule's position u = f_half H + f_h clocks after CS fell; a pin
  // edge shows one clock after the schedule's counters took it).
  wire [23:0] f_u = {18'd0, f_half} * {8'd0, F_H} + {8'd0, f_h};
  wire f_e0 = f_conv && f_half == 6'd0 && f_h == 16'd0;  // CS just fell
  always @(*)
    if (f_past) begin
      assert (p_cs == (f_e0 || (!f_conv && !e_csr)));
      if (f_conv && !f_e0) assert (p_csf == f_u && p_nf + {4'd0, e_fall} == 5'((f_half + 6'd1) >> 1)
                                   && p_nr + {4'd0, e_rise} == 5'(f_half >> 1));
      if (!f_conv && p_csf < F_PER) assert (p_csf + 24'd1 == F_PER ? f_pc == 16'd0 : {8'd0, f_pc} == p_csf + 24'd1);
      if (!f_conv && p_en) assert (p_csf < F_PER);
      if (!f_conv) assert (p_nf == 5'd16 && p_nr + {4'd0, e_rise} == 5'd16 || p_nf == 5'd0 && p_nr == 5'd0 && f_gap == 16'hFFFF);
      if (!f_conv && p_nf == 5'd0) assert (p_csf == F_SAT && p_csr == F_SAT && p_13 == F_SAT && p_16 == F_SAT);
      if (e_csr) assert (p_csf == 24'd32 * {8'd0, F_H} && p_16 == {8'd0, F_H} && p_13 == 24'd7 * {8'd0, F_H});
      if (!f_conv && p_nf == 5'd16 && !e_csr) begin
        if (f_gap != 16'hFFFF) assert (p_csr == {8'd0, f_gap});
        else assert (p_csr >= 24'd65535);
        assert (p_16 == (p_csr > F_SAT - {8'd0, F_H} ? F_SAT : p_csr + {8'd0, F_H}));
        assert (p_13 == (p_csr > F_SAT - 24'd7 * {8'd0, F_H} ? F_SAT : p_csr + 24'd7 * {8'd0, F_H}));
        assert (p_csf == (p_csr > F_SAT - 24'd32 * {8'd0, F_H} ? F_SAT : p_csr + 24'd32 * {8'd0, F_H}));
      end
      if (f_conv && !f_e0) begin
        assert (p_csr >= p_csf + F_T1);
        if (f_half < 6'd25 || (f_half == 6'd25 && e_fall)) assert (p_13 >= p_csf + F_ACQ);
        else assert (p_13 == p_csf - 24'd25 * {8'd0, F_H});
        if (f_half < 6'd31 || (f_half == 6'd31 && e_fall)) assert (p_16 >= p_csf + F_QUIET);
        else assert (p_16 == p_csf - 24'd31 * {8'd0, F_H});
      end
      if (f_conv && f_half[0] && !e_fall) assert (p_fall == {8'd0, f_h});
      if (f_conv && !f_half[0] && f_half >= 6'd2) assert (p_fall == {8'd0, F_H + f_h});
      if (f_conv && !f_half[0] && f_half >= 6'd2 && !e_rise) assert (p_rise == {8'd0, f_h});
      if (f_conv && f_half[0] && f_half >= 6'd3) assert (p_rise == {8'd0, F_H + f_h});
      if (f_conv && (f_half >= 6'd4 || (f_half == 6'd3 && !e_fall))) assert (p_hi == {8'd0, F_H});
      assert ((LAG == 0 && e_fall) ? shreg == p_shn : shreg == p_sh);
      if (LAG != 0) assert (p_16q == f_got16);
    end
  always @(posedge clk)
    if (f_past) begin
      cover (f_got16 && !f_full);                 // a code delivered
      cover (f_got16 && f_full);                  // an overrun
      cover (!cs_n && f_half == 6'd0 && f_gap != 16'hFFFF && f_gap != 16'd0);  // a second conversion
      cover (e_csf && p_nf == 5'd16 && p_csf == F_PER);         // back to back: CS falls PERIOD on
      cover (e_csf && p_nf == 5'd16 && p_csf > F_PER);          // en low for a while: later
      cover (e_csr && p_nf == 5'd16);                           // 16 SCLK cycles, CS up
      cover (p_done && !p_full && m_data[11:0] == 12'hA5C);    // a code from SDATA
      cover (p_done && p_full);                                 // an overrun: the token kept
    end
`endif
endmodule
`default_nettype wire
