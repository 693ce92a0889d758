// frame_engine: the microcoded arithmetic unit behind the DTMF top
// (docs/frame_engine.md: ISA, encoding, timing). Clock-exact executable spec:
// ucode/frame_engine.h; the two are compared instruction by instruction in
// tests/rtl/frame_engine_test.cpp.
//
// Organisation (area first: one 48-bit adder, one logic unit, a 1-bit/clock
// shifter and a 2-clock/digit square root, all writing A; FAST_SHIFT = 1
// adds a barrel shifter, so shl/shr/rnd take one B clock for any count, and
// the root takes two digits a clock):
//   cycle A  IR (the IMEM read port's output register) is decoded; ea =
//            addr + X[x] addresses DMEM, KROM and the IO bus (io_re); jumps,
//            calls, returns and X writes take effect at the end of A, and
//            the decoded controls of cycle B are registered (u_*).
//   cycle B  the operand bus y = m ^ sub (m: a field of DMEM/KROM/IO/A[31:0],
//            the immediate, P, ea, the shifted A or the root) meets A in the
//            adder (A + y + cin) and the logic unit (~y, A & y, A | y,
//            A ^ y); A, T, P, DMEM (st) and IO (out) are written at the end
//            of B. shl/shr/rnd, min/max, sqrt/sqrtr and wait stay in B for
//            more clocks (docs: timing).
// Overlap: the next instruction's cycle A runs in the current one's last B
// clock (a_go), and cycle A fetches the one after it, so most instructions
// take one clock. A waits for a clock of its own when it reads A (j on a
// condition, tax, sqrt/sqrtr) while the B clock may write A, reads DMEM
// after `st` (one port: SPRAM) or IO after `out`, and after a B whose
// last clock is known only in it (wait, a loaded shift count of 0). The
// B clock is "last" by flip-flops only (b_last, b_writes_a), so no B-clock
// result reaches cycle A's enables.
// Memories: IMEM 2^IW x 32 ROM ($readmemh UCODE_HEX), KROM 2^KW x 32 ROM
// (KROM_INIT, word k at [32k +: 32]), DMEM 2^DW x 32 single-port RAM, not
// initialised: EBR for DW <= 9, SPRAM for DW >= 10 (ram_style "huge": two
// SB_SPRAM256KA, four for DW = 15; no -spram option needed).
`default_nettype none

module frame_engine #(
    parameter integer IW = 9,          // IMEM address bits (4..12)
    parameter integer DW = 8,          // DMEM address bits (4..15)
    parameter integer KW = 8,          // KROM address bits (1..12)
    parameter integer IMEM_WORDS = 1 << IW,  // IMEM depth (<= 2^IW; the program must fit)
    parameter UCODE_HEX = "",          // IMEM contents ("": none)
    parameter KROM_HEX = "",           // KROM contents as a $readmemh file, else KROM_INIT
    parameter [32*(1<<KW)-1:0] KROM_INIT = 0,
    // 1: shl/shr/rnd shift in one clock (two 48-bit barrel shifters, about
    // 1000 ECP5 logic cells: for the larger FPGAs); 0: one bit per clock.
    parameter integer FAST_SHIFT = 0
) (
    input  wire        clk,
    input  wire        rst,            // synchronous, active high
    output wire [15:0] io_raddr,       // cycle A of an IO read (with io_re)
    output wire        io_re,          // cycle A of an IO read
    output wire [15:0] io_waddr,       // cycle B of `out` (with io_we), registered
    input  wire [31:0] io_rdata,       // used in the first clock of B
    output wire        io_we,          // cycle B of `out`
    output wire [31:0] io_wdata,
    input  wire [15:0] events          // `wait` ends when (events & mask) != 0
);
  generate
    if (IW < 4 || IW > 12) begin : g_bad_iw
      frame_engine_parameter_IW_must_be_4_to_12 stop();
    end
    if (DW < 4 || DW > 15) begin : g_bad_dw
      frame_engine_parameter_DW_must_be_4_to_15 stop();
    end
    if (KW < 1 || KW > 12) begin : g_bad_kw
      frame_engine_parameter_KW_must_be_1_to_12 stop();
    end
    if (IMEM_WORDS < 16 || IMEM_WORDS > (1 << IW)) begin : g_bad_imem
      frame_engine_parameter_IMEM_WORDS_must_be_16_to_2_pow_IW stop();
    end
    if (FAST_SHIFT != 0 && FAST_SHIFT != 1) begin : g_bad_fast_shift
      frame_engine_parameter_FAST_SHIFT_must_be_0_or_1 stop();
    end
  endgenerate

  // ---- encoding (docs/frame_engine.md) ------------------------------------
  localparam [1:0] C_MEM = 2'd0, C_IMM = 2'd1, C_P = 2'd2, C_CTL = 2'd3;
  localparam [3:0] F_LD = 4'd0, F_ADD = 4'd1, F_SUB = 4'd2, F_MIN = 4'd3, F_MAX = 4'd4,
                   F_XOR = 4'd7, F_LT = 4'd8, F_MPY = 4'd9, F_SHL = 4'd10,
                   F_RND = 4'd12, F_ST = 4'd13, F_OUT = 4'd14;
  localparam [3:0] K_J = 4'd0, K_DJNZ = 4'd1, K_CALL = 4'd2, K_RET = 4'd3, K_WAIT = 4'd4,
                   K_SQRT = 4'd5, K_SQRTR = 4'd6, K_LDX = 4'd7, K_ADDX = 4'd8,
                   K_TAX = 4'd9, K_TXA = 4'd10;
  // 25 root digits: two clocks each; with FAST_SHIFT two digits a clock (A
  // moves four bits a clock; the first clock takes two zero bits and two of A)
  localparam [5:0] SQ_STEPS = FAST_SHIFT != 0 ? 6'd13 : 6'd50;

  // ---- architectural state ---------------------------------------------------
  reg  [31:0]  ir;
  reg  [IW-1:0] pc;
  reg  [47:0]  acc;                    // A
  reg  [15:0]  t;
  reg  [31:0]  p;
  reg  [15:0]  x1, x2, x3;
  reg  [IW-1:0] stk0, stk1;            // return stack: stk0 on top

  // ---- sequencing state --------------------------------------------------------
  reg          bact;                   // a B clock runs in this clock
  wire         a_go;                   // cycle A runs in this clock
  reg  [5:0]   cnt;                    // shift / sqrt steps left
  reg          rbit;                   // last bit shifted out (rnd)
  reg  [25:0]  rem;                    // sqrt partial remainder
  reg  [24:0]  root;                   // root digits so far (of 4 A)
  reg          sqneg;                  // sqrt of a negative A: result 0
  // Controls of the current B clock, registered (decoded from IR at the end
  // of A, advanced at the end of each B clock of a multi-clock instruction).
  reg u_sel_i, u_sel_x, u_sel_q, u_step;  // operand m source (besides the field)
  // Field of the word w (all 0 unless the operand is a memory/P word): where
  // fv's bits come from (see the field table in the operand section).
  reg u_f_lo, u_f_mid, u_f_15, u_f_hi, u_f_h, u_f_h15, u_e15, u_e31, u_e31t;
  reg u_sub;                           // y = ~m, cin = 1
  reg [1:0] u_lop;                     // logic unit: ~y, A & y, A | y, A ^ y
  reg u_use_s;                         // A takes s (else lg)
  reg u_we, u_min, u_max;              // A written: always, if A >= m, if A < m
  reg u_cin_r, u_cin_q;                // cin = rbit (rnd), = root[0] (sqrtr)
  reg u_lt, u_mpy, u_st, u_out;
  reg u_put;                           // min/max second clock: A = m unless keep_r
  reg u_left;                          // shift direction (shl, sqrt)
  reg u_latch;                         // this clock loads the shift count from y
  reg u_shift, u_rnd, u_sq, u_wait;    // the instruction in B
  reg u_sqr;                           // ... is sqrtr (IR holds the next one)
  reg u_bar;                           // FAST_SHIFT: this clock shifts A by cnt at once

  wire [1:0]  cls = ir[31:30];
  wire [3:0]  fn = ir[29:26];
  wire [1:0]  space = ir[25:24];
  wire [1:0]  xs = ir[23:22];
  wire [2:0]  fld = ir[21:19];         // operand field; jump condition
  wire [15:0] addr = ir[15:0];
  wire        ctl = cls == C_CTL;
  wire        memop = cls == C_MEM;

  // ---- effective address --------------------------------------------------
  // X[xs] is added whatever the class, so the adder starts from IR's bits
  // (cycle A's long path: IMEM bank mux -> X mux -> adder -> memory
  // address); ldx, which ignores the index, takes the plain field instead
  // (xval below).
  reg  [15:0] xv;
  always @* begin
    case (xs)
      2'd1: xv = x1;
      2'd2: xv = x2;
      2'd3: xv = x3;
      default: xv = 16'd0;
    endcase
  end
  wire [15:0] ea = addr + xv;

  // Cycle B works from registered copies of IR and ea (taken at the end of
  // A): B's long path (operand select -> 48-bit adder -> A) then starts at
  // flip-flops instead of at the IMEM block RAM's output and its bank mux.
  reg  [1:0]  cls_b;
  reg  [25:0] irb;                     // IR[25:0] (IR[29:26], the function, is decoded in A)
  reg  [15:0] eab;
  always @(posedge clk) if (a_go) {cls_b, irb, eab} <= {ir[31:30], ir[25:0], ea};
  wire [1:0] space_b = irb[25:24];
  reg  [15:0] xv_b;                    // X of the instruction in B (txa)
  always @* begin
    case (irb[23:22])
      2'd1: xv_b = x1;
      2'd2: xv_b = x2;
      2'd3: xv_b = x3;
      default: xv_b = 16'd0;
    endcase
  end

  // ---- memories -----------------------------------------------------------
  reg [31:0] imem [0:IMEM_WORDS-1];
  reg [31:0] krom [0:(1<<KW)-1];
  // Yosys: SPRAM from 1K words on (the UP5K's EBRs are scarce), else EBR.
  /* verilator lint_off UNUSEDPARAM */
  localparam DMEM_STYLE = DW >= 10 ? "huge" : "block";
  /* verilator lint_on UNUSEDPARAM */
  (* ram_style = DMEM_STYLE *) reg [31:0] dmem [0:(1<<DW)-1];
  reg [31:0] kq, dq;
  integer k;
`ifdef ESKIN_HEX_PLUSARGS
  // The virtual board's models (Verilator -DESKIN_HEX_PLUSARGS) are given
  // their files at run time (+UCODE_HEX=PATH, +KROM_HEX=PATH): each run's
  // microcode goes to its user's own directory, not into a build tree
  // shared by every user (sim/vboard/fpga_params.h, RunFiles). Other
  // simulations and synthesis read the parameters' files.
  reg [8*1024-1:0] ucode_file, krom_file;
  initial begin
    if ($value$plusargs("UCODE_HEX=%s", ucode_file)) $readmemh(ucode_file, imem);
    else if (UCODE_HEX != "") $readmemh(UCODE_HEX, imem);
    if ($value$plusargs("KROM_HEX=%s", krom_file)) $readmemh(krom_file, krom);
    else if (KROM_HEX != "") $readmemh(KROM_HEX, krom);
    else for (k = 0; k < (1 << KW); k = k + 1) krom[k] = KROM_INIT[32*k +: 32];
  end
`else
  initial begin
    if (UCODE_HEX != "") $readmemh(UCODE_HEX, imem);
    if (KROM_HEX != "") $readmemh(KROM_HEX, krom);
    else for (k = 0; k < (1 << KW); k = k + 1) krom[k] = KROM_INIT[32*k +: 32];
  end
`endif

  // One address for both ports so the SPRAM (single-ported) can hold it:
  // B writes at its registered ea, A reads at the decoded one (never in the
  // same clock: a DMEM read after `st` waits, see a_go).
  wire st_b = bact && u_st;
  wire [DW-1:0] dmem_a = st_b ? eab[DW-1:0] : ea[DW-1:0];
  always @(posedge clk) begin
    if (st_b) dmem[dmem_a] <= acc[31:0];
    else if (a_go) dq <= dmem[dmem_a];
  end
  always @(posedge clk) if (a_go) kq <= krom[ea[KW-1:0]];

  assign io_raddr = ea;
  assign io_waddr = eab;
  assign io_re = a_go && io_rd;
  assign io_we = bact && u_out;
  assign io_wdata = acc[31:0];

  // ---- operand ----------------------------------------------------------------
  // The word w: P for the P class, else the space's word.
  reg [31:0] w;
  always @* begin
    if (cls_b == C_P) w = p;
    else begin
      case (space_b)
        2'd0: w = dq;
        2'd1: w = kq;
        2'd2: w = io_rdata;
        default: w = acc[31:0];
      endcase
    end
  end
  // The field fv of w (.w sext(w), .wu zext(w), .l sext(w[15:0]), .lu
  // zext(w[15:0]), .h sext(w[31:16]), .l15 zext(w[14:0]), .h15 sext(w[31:15]),
  // .b zext(w[7:0])), as an AND-OR of w's bits under the decoded selects.
  wire ext_mid = (u_e15 & w[15]) | (u_e31 & w[31]);
  wire ext_top = (u_e15 & w[15]) | (u_e31t & w[31]);
  wire [47:0] fv = {{16{ext_top}},
                    ({16{u_f_hi}} & w[31:16]) | {16{ext_mid}},
                    (u_f_15 & w[15]) | (u_f_h & w[31]) | (u_f_h15 & w[30]),
                    ({7{u_f_mid}} & w[14:8]) | ({7{u_f_h}} & w[30:24]) | ({7{u_f_h15}} & w[29:23]),
                    ({8{u_f_lo}} & w[7:0]) | ({8{u_f_h}} & w[23:16]) | ({8{u_f_h15}} & w[22:15])};
  // One step of a shift or of sqrt; with FAST_SHIFT only sqrt steps (four
  // bits left: its radicand's next four bits go to rem each clock; two in
  // the first, behind two zero bits: sq_first below).
  wire sq_first = cnt == SQ_STEPS;
  wire [47:0] sha = FAST_SHIFT == 0 ? (u_left ? {acc[46:0], 1'b0} : {acc[47], acc[47:1]}) :
                    sq_first ? {acc[45:0], 2'b00} : {acc[43:0], 4'b0000};
  // Barrel shifts by cnt (FAST_SHIFT; constant-0 u_bar removes them
  // otherwise). A 49-bit right shift of {A, 0} gives floor(A / 2^n) in its
  // top 48 bits and bit n - 1 of A, rnd's rounding bit, in bit 0 (the sign
  // for n > 48, as the model's rnd has it).
  wire [48:0] bar_r = $signed({acc, 1'b0}) >>> cnt;
  wire [47:0] bar_l = acc << cnt;
  wire [47:0] bar = u_left ? bar_l : bar_r[48:1];
  // The barrel's result goes straight to A (acc_d), not through m and the
  // adder: a shift clock adds nothing, and the path barrel -> adder -> A,
  // false but seen by the timing analysis, was the UP5K's critical path.
  wire [47:0] m = fv | ({48{u_sel_i}} & {{22{irb[25]}}, irb[25:0]}) |
                  ({48{u_sel_x}} & {32'd0, xv_b}) | ({48{u_step}} & sha) |
                  ({48{u_sel_q}} & {24'd0, root[24:1]});

  // ---- ALU: s = A + y + cin, lg = ~y / A & y / A | y / A ^ y ----------------
  // u_sub = 1 also where A takes m through the logic unit (lg = ~y = m).
  wire [47:0] y = m ^ {48{u_sub}};
  wire cin = u_sub | (u_cin_r & rbit) | (u_cin_q & root[0]);
  // Carry-select: the upper 25 bits are added for both carries out of the
  // lower 24 at once, then picked, so B's path holds a 24-bit carry chain
  // instead of a 48-bit one (the top's critical path: 18 ns of carry).
  wire [24:0] s_lo = {1'b0, acc[23:0]} + {1'b0, y[23:0]} + {24'd0, cin};
  wire [24:0] s_hi0 = {acc[47], acc[47:24]} + {y[47], y[47:24]};
  wire [24:0] s_hi1 = {acc[47], acc[47:24]} + {y[47], y[47:24]} + 25'd1;
  wire [48:0] s = {s_lo[24] ? s_hi1 : s_hi0, s_lo[23:0]};
  wire a_lt_m = s[48];                 // sign of the exact 49-bit A - m
  reg [47:0] lg;
  always @* begin
    case (u_lop)
      2'd1: lg = acc & y;
      2'd2: lg = acc | y;
      2'd3: lg = acc ^ y;
      default: lg = ~y;
    endcase
  end
  // min/max take two B clocks: the first registers the comparison (the
  // adder's carry out, B's latest signal), the second writes m (lg = ~y = m)
  // or leaves A, so A's clock enable starts at a flip-flop.
  // m is kept too: an IO word is only valid in B's first clock.
  reg keep_r;                          // min/max: A stays (registered compare)
  reg [47:0] m_r;                      // min/max: m of the first clock
  always @(posedge clk)
    if (u_min || u_max) begin
      keep_r <= (u_min && a_lt_m) || (u_max && !a_lt_m);
      m_r <= m;
    end
  wire acc_we = bact && (u_we || (u_put && !keep_r));
  wire [47:0] acc_d = u_bar ? bar : u_use_s ? s[47:0] : u_put ? m_r : lg;

  // ---- square root of 4 A: one root digit per two clocks -------------------
  // cnt = 50..1: A shifts left and its top bit enters rem (two zero bits
  // follow A's 48); at odd cnt the trial rem - (4 root + 1) decides the next
  // digit. 25 digits give root = floor(sqrt(4 A)) = floor(2 sqrt(A)), so
  // sqrt = root >> 1 and sqrtr = (root + 1) >> 1, added to A (then 0) in the
  // final clock.
  wire [26:0] rsh = {rem, acc[47]};
  wire [27:0] dif = {1'b0, rsh} - {1'b0, root, 2'b01};
  wire dig = !dif[27] && !sqneg;
  wire unused_dif = dif[26];           // 0 whenever dig = 1: rem <= 2 root < 2^26
  // FAST_SHIFT: two digits every clock, the step above twice in a row on
  // A's next four bits: {0, 0, A[47:46]} first (a leading 0 digit, then
  // A's first: 26 digits in 13 clocks, the 0 shifted out of root at the
  // end), then A[47:44] as A moves four bits a clock.
  wire [3:0] sq4 = sq_first ? {2'b00, acc[47:46]} : acc[47:44];
  wire [27:0] rsa = {rem, sq4[3:2]};
  wire [28:0] dfa = {1'b0, rsa} - {2'b00, root, 2'b01};
  wire dga = !dfa[28] && !sqneg;
  wire [25:0] rma = dga ? dfa[25:0] : rsa[25:0];
  wire [24:0] rta = {root[23:0], dga};  // root[24] is the leading 0 until the last clock
  wire [27:0] rsb = {rma, sq4[1:0]};
  wire [28:0] dfb = {1'b0, rsb} - {2'b00, rta, 2'b01};
  wire dgb = !dfb[28] && !sqneg;
  // All 0 where used: with a digit, rem <= 2 root < 2^26; without, the
  // trial value < 4 root + 1 < 2^26 (root < 2^24 before its last digits).
  wire [7:0] unused_sq2 = {dfa[27:26], rsa[27:26], dfb[27:26], rsb[27:26]};

  // ---- control flow -----------------------------------------------------------
  wire zf = acc == 48'd0;
  reg ctaken;
  always @* begin
    case (fld[1:0])
      2'd0: ctaken = 1'b1;
      2'd1: ctaken = zf;
      2'd2: ctaken = acc[47];
      default: ctaken = acc[47] | zf;
    endcase
  end
  wire [15:0] xdec = xv - 16'd1;
  wire xdec_nz = xv != 16'd1;
  wire [IW-1:0] pc1 = pc + 1'b1;
  wire [IW-1:0] target = addr[IW-1:0];

  // Next PC and X, at the end of cycle A.
  wire call_op = ctl && fn == K_CALL;
  wire ret_op = ctl && fn == K_RET;
  wire jump = (ctl && fn == K_J && (ctaken ^ fld[2])) || (ctl && fn == K_DJNZ && xdec_nz) ||
              call_op;
  wire [IW-1:0] pc_next = jump ? target : ret_op ? stk0 : pc1;
  wire x_we = ctl && (fn == K_DJNZ || fn == K_LDX || fn == K_ADDX || fn == K_TAX);
  wire [15:0] xval = fn == K_DJNZ ? xdec : fn == K_TAX ? acc[15:0] : fn == K_LDX ? addr : ea;
  // Return stack: call pushes (the older entry falls off), ret pops (the
  // bottom entry stays).
  always @(posedge clk) begin
    if (rst) begin
      stk0 <= {IW{1'b0}};
      stk1 <= {IW{1'b0}};
    end else if (a_go && (call_op || ret_op)) begin
      stk0 <= call_op ? pc1 : stk1;
      if (call_op) stk1 <= stk0;
    end
  end
`ifndef SYNTHESIS
  // Return stack overflow (simulation only: no logic on the chip): a call
  // made while both entries hold live return addresses loses the older
  // one. stk_depth counts the live entries (a ret at 0 leaves it 0),
  // stk_overflows the calls that overflowed since reset, as the model's
  // stack_overflows() does (tests/rtl/frame_engine_test.cpp compares them
  // in every random program, whose calls overflow at will: those tests
  // switch assertions off). With assertions on (Verilator --assert, every
  // build of a top) the first overflow stops the simulation.
  reg [1:0]  stk_depth;
  reg [31:0] stk_overflows;
  always @(posedge clk) begin
    if (rst) begin
      stk_depth <= 2'd0;
      stk_overflows <= 32'd0;
    end else if (a_go && call_op) begin
      if (stk_depth == 2'd2) stk_overflows <= stk_overflows + 32'd1;
      else stk_depth <= stk_depth + 2'd1;
    end else if (a_go && ret_op && stk_depth != 2'd0) begin
      stk_depth <= stk_depth - 2'd1;
    end
  end
  always @(posedge clk)
    if (!rst && a_go && call_op)
      assert (stk_depth != 2'd2)
      else $error("frame_engine: return stack overflow: the call at PC %0d is a third nested call (two entries; docs/frame_engine.md)", pc);
`endif

  // ---- end of the current B clock ---------------------------------------------
  wire last_step = cnt == 6'd1;
  reg done;
  always @* begin
    if (u_latch) done = y[5:0] == 6'd0;
    else if (u_step) done = u_shift && !u_rnd && last_step;
    else if (u_bar) done = !u_rnd;
    else if (u_wait) done = |(events & irb[15:0]);
    else done = !(u_min || u_max);
  end
  // done, where it is known from flip-flops alone (never for a wait or the
  // clock that loads a shift count): the next cycle A may run in this clock.
  reg b_last;
  always @* begin
    if (u_latch || u_wait || u_min || u_max) b_last = 1'b0;
    else if (u_step) b_last = u_shift && !u_rnd && last_step;
    else if (u_bar) b_last = !u_rnd;
    else b_last = 1'b1;
  end

  // ---- when cycle A runs --------------------------------------------------------
  wire io_rd = memop && space == 2'd2 && fn <= F_RND;
  wire dm_rd = memop && space == 2'd0 && fn <= F_RND;
  wire reads_a = ctl && ((fn == K_J && fld[1:0] != 2'd0) || fn == K_TAX || fn == K_SQRT || fn == K_SQRTR);
  // A read of A waits only for a B clock that may write it (u_we, or
  // min/max's second clock): after st, out, lt, mpy or a control
  // instruction A is already final. Flip-flops only, as b_last.
  wire b_writes_a = u_we || u_put;
  wire hazard = (reads_a && b_writes_a) || (u_st && dm_rd) || (u_out && io_rd);
  assign a_go = !rst && (!bact || (b_last && !hazard));

  // T and P. P has no reset of its own, so that it stays the SB_MAC16's
  // output register: reset clears T, and a second reset clock writes
  // P = 0 * y = 0 (reset must last at least two clocks).
  always @(posedge clk) begin
    if (rst) t <= 16'd0;
    else if (bact && u_lt) t <= y[15:0];
  end
  always @(posedge clk) begin
    if (rst || (bact && u_mpy)) p <= $signed({{16{t[15]}}, t}) * $signed({{16{y[15]}}, y[15:0]});
  end

  // Fetch: the IMEM read port's register is IR; cycle A reads the next
  // instruction at the PC it chooses; IMEM[0] is read during reset.
  always @(posedge clk) if (rst || a_go) ir <= imem[rst ? {IW{1'b0}} : pc_next];

  // Decoded controls of B's first clock.
  wire alu_op = !ctl && fn <= F_XOR;
  wire shift_op = !ctl && (fn == F_SHL || fn == 4'd11 || fn == F_RND);
  wire imm_steps = shift_op && cls == C_IMM && ir[5:0] != 6'd0;
  wire fast = FAST_SHIFT != 0;
  wire sq_op = ctl && (fn == K_SQRT || fn == K_SQRTR);
  wire txa_op = ctl && fn == K_TXA;
  wire reads_m = !ctl && fn <= F_RND && !imm_steps;
  wire sel_w = reads_m && cls != C_IMM;  // the operand is a field of w

  // Square root registers: cleared at the end of cycle A of sqrt/sqrtr.
  wire sq_clear = rst || (a_go && sq_op);
  always @(posedge clk) begin
    if (sq_clear) begin
      rem <= 26'd0;
      root <= 25'd0;
    end else if (bact && u_sq && u_step) begin
      if (FAST_SHIFT != 0) begin
        rem <= dgb ? dfb[25:0] : rsb[25:0];
        root <= {rta[23:0], dgb};
      end else begin
        rem <= (cnt[0] && dig) ? dif[25:0] : rsh[25:0];
        if (cnt[0]) root <= {root[23:0], dig};
      end
    end
  end
  always @(posedge clk) if (a_go) sqneg <= acc[47];

  always @(posedge clk) begin
    if (rst) begin
      bact <= 1'b0; pc <= {IW{1'b0}}; acc <= 48'd0;
      x1 <= 16'd0; x2 <= 16'd0; x3 <= 16'd0;
      cnt <= 6'd0; rbit <= 1'b0;
      {u_sel_i, u_sel_x, u_sel_q, u_step} <= 4'd0;
      {u_f_lo, u_f_mid, u_f_15, u_f_hi, u_f_h, u_f_h15, u_e15, u_e31, u_e31t} <= 9'd0;
      {u_sub, u_lop, u_use_s, u_we, u_min, u_max, u_cin_r, u_cin_q} <= 9'd0;
      {u_lt, u_mpy, u_st, u_out, u_left, u_latch, u_shift, u_rnd, u_sq, u_wait} <= 10'd0;
      u_put <= 1'b0;
      u_bar <= 1'b0;
      u_sqr <= 1'b0;
    end else begin
      if (bact) begin
        // ---- end of a clock of cycle B
        if (done) bact <= 1'b0;
        if (acc_we) acc <= acc_d;
        if (u_min || u_max) begin          // compared: the write follows
          u_min <= 1'b0;
          u_max <= 1'b0;
          u_put <= 1'b1;
        end
        if (u_step) begin
          cnt <= cnt - 6'd1;
          rbit <= acc[0];
        end
        if (u_bar) rbit <= bar_r[0];
        // Controls of the next B clock of a multi-clock instruction.
        if (u_latch) begin                 // count loaded: steps follow
          cnt <= y[5:0];
          u_sel_i <= 1'b0;
          {u_f_lo, u_f_mid, u_f_15, u_f_hi, u_f_h, u_f_h15, u_e15, u_e31, u_e31t} <= 9'd0;
          u_latch <= 1'b0;
          u_step <= !fast;
          u_bar <= fast;
          u_sub <= 1'b1;
          u_we <= 1'b1;
        end
        if ((u_step && last_step && (u_rnd || u_sq)) || (u_bar && u_rnd)) begin  // final clock: A + y + cin
          u_step <= 1'b0;
          u_bar <= 1'b0;
          u_sub <= 1'b0;
          u_use_s <= 1'b1;
          u_sel_q <= u_sq;
          u_cin_r <= u_rnd;
          u_cin_q <= u_sqr;
        end
      end
      // Cycle A last, so that its controls replace those of a B clock that ends.
      if (a_go) begin
        // ---- end of cycle A: control flow, X, the controls of B
        bact <= 1'b1;
        pc <= pc_next;
        if (x_we && xs == 2'd1) x1 <= xval;
        if (x_we && xs == 2'd2) x2 <= xval;
        if (x_we && xs == 2'd3) x3 <= xval;
        rbit <= 1'b0;
        cnt <= sq_op ? SQ_STEPS : ir[5:0];
        u_f_lo <= sel_w && fld != 3'd4 && fld != 3'd6;
        u_f_mid <= sel_w && fld != 3'd4 && fld != 3'd6 && fld != 3'd7;
        u_f_15 <= sel_w && fld <= 3'd3;
        u_f_hi <= sel_w && fld <= 3'd1;
        u_f_h <= sel_w && fld == 3'd4;
        u_f_h15 <= sel_w && fld == 3'd6;
        u_e15 <= sel_w && fld == 3'd2;
        u_e31 <= sel_w && (fld == 3'd4 || fld == 3'd6);
        u_e31t <= sel_w && (fld == 3'd0 || fld == 3'd4 || fld == 3'd6);
        u_sel_i <= reads_m && cls == C_IMM;
        u_sel_x <= txa_op;
        u_sel_q <= 1'b0;
        u_step <= (imm_steps && !fast) || sq_op;
        u_bar <= imm_steps && fast;
        u_sub <= (alu_op && (fn == F_LD || fn == F_SUB || fn == F_MIN || fn == F_MAX)) ||
                 imm_steps || sq_op || txa_op;
        u_lop <= (alu_op && fn[2]) ? fn[1:0] : 2'd0;
        u_use_s <= alu_op && (fn == F_ADD || fn == F_SUB);
        u_we <= (alu_op && fn != F_MIN && fn != F_MAX) || imm_steps || sq_op || txa_op;
        u_min <= alu_op && fn == F_MIN;
        u_max <= alu_op && fn == F_MAX;
        u_put <= 1'b0;
        u_cin_r <= 1'b0;
        u_cin_q <= 1'b0;
        u_lt <= !ctl && fn == F_LT;
        u_mpy <= !ctl && fn == F_MPY;
        u_st <= memop && fn == F_ST;
        u_out <= memop && fn == F_OUT;
        u_left <= (!ctl && fn == F_SHL) || sq_op;
        u_latch <= shift_op && cls != C_IMM;
        u_shift <= shift_op;
        u_rnd <= !ctl && fn == F_RND;
        u_sq <= sq_op;
        u_wait <= ctl && fn == K_WAIT;
        u_sqr <= ctl && fn == K_SQRTR;
      end
    end
  end
endmodule
`default_nettype wire
