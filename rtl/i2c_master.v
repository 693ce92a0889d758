`default_nettype none
// i2c_master: one open-drain I2C bus master, byte-level commands in,
// one response per command out.
//
// Pins: scl_oe / sda_oe high pull the line low, low release it (an external
// or pad pull-up makes the high level); scl_i / sda_i are the line levels,
// read through 2-flop synchronisers.
//
// Commands (cmd_valid/cmd_ready, cmd_op, cmd_data, cmd_ack):
//   OP_START   START, or a repeated START when the bus is already ours.
//              From idle both lines must read high, else ERR_BUSY.
//   OP_WRITE   send cmd_data MSB first, read the ACK bit: rsp_nack = 1 when
//              the target did not pull SDA low.
//   OP_READ    read a byte into rsp_data, then ACK it (cmd_ack = 1: more
//              bytes wanted) or NACK it (the last byte).
//   OP_STOP    STOP; waits tBUF before the response so the next START is
//              legal. A no-op when the bus is not ours.
//   OP_RECOVER bus recovery: while SDA reads low, up to 9 SCL pulses with SDA
//              released (a target stuck mid-byte shifts out its remaining
//              bits and releases SDA at the ACK slot); then STOP. rsp_data =
//              pulses given; ERR_STUCK if SDA is still low after 9.
// Response (rsp_valid/rsp_ready): rsp_data, rsp_nack, rsp_err (ERR_OK,
// ERR_BUSY, ERR_TIMEOUT: SCL held low by someone else for longer than
// TIMEOUT_US, or SDA not released after our STOP for as long -- the master
// then releases both lines and gives up the bus --, ERR_STUCK).
//
// Timing (UM10204, fast-mode above 100 kHz, else standard-mode), in clocks
// of CLK_HZ, each rounded up:
//   LOW  = max(tLOW, 1/SCL_HZ - HIGH - 2)   SCL low phase, from our pull-down
//   HIGH = tHIGH, counted from when the synchronised SCL reads high, so a
//          target's clock stretching and the rise time only lengthen the bit
//   SDA changes HOLD (about 300 ns) after SCL falls and is sampled at the
//   middle of HIGH; START hold tHD;STA, repeated START setup tSU;STA, STOP
//   setup tSU;STO (from SCL seen high), bus free tBUF (from SDA seen high).
// TLOW_NS / THIGH_NS can be overridden only to build negative controls (a
// master the bus checker must reject); SCL_HZ above 400 kHz, too slow a
// clock, or a timeout shorter than a bit stop elaboration.
module i2c_master #(
    parameter integer CLK_HZ = 12_000_000,
    parameter integer SCL_HZ = 400_000,
    parameter integer TIMEOUT_US = 1000,
    parameter integer TLOW_NS = (SCL_HZ > 100_000) ? 1300 : 4700,
    parameter integer THIGH_NS = (SCL_HZ > 100_000) ? 600 : 4000
) (
    input  wire       clk,
    input  wire       rst,
    input  wire       cmd_valid,
    output wire       cmd_ready,
    input  wire [2:0] cmd_op,
    input  wire [7:0] cmd_data,
    input  wire       cmd_ack,
    output reg        rsp_valid,
    input  wire       rsp_ready,
    output reg  [7:0] rsp_data,
    output reg        rsp_nack,
    output reg  [1:0] rsp_err,
    input  wire       scl_i,
    input  wire       sda_i,
    output reg        scl_oe,
    output reg        sda_oe,
    output reg        owned  // between our START and STOP
);
  localparam [2:0] OP_START = 3'd0, OP_WRITE = 3'd1, OP_READ = 3'd2, OP_STOP = 3'd3,
                   OP_RECOVER = 3'd4;
  localparam [1:0] ERR_OK = 2'd0, ERR_BUSY = 2'd1, ERR_TIMEOUT = 2'd2, ERR_STUCK = 2'd3;

  localparam FAST = SCL_HZ > 100_000;
  localparam integer CLK_KHZ = CLK_HZ / 1000;
  function integer cyc(input integer ns);  // ns -> clocks, rounded up
    cyc = (CLK_KHZ * ns + 999_999) / 1_000_000;
  endfunction
  localparam integer PERIOD_CYC = (CLK_HZ + SCL_HZ - 1) / SCL_HZ;
  localparam integer HIGH_CYC = cyc(THIGH_NS);
  localparam integer LOW_SPEC = cyc(TLOW_NS);
  localparam integer LOW_CYC = (PERIOD_CYC - HIGH_CYC - 2 > LOW_SPEC) ?
                               PERIOD_CYC - HIGH_CYC - 2 : LOW_SPEC;
  localparam integer HOLD_CYC = (cyc(300) > 1) ? cyc(300) : 1;
  localparam integer HD_STA_CYC = cyc(FAST ? 600 : 4000);
  localparam integer SU_STA_CYC = cyc(FAST ? 600 : 4700);
  localparam integer SU_STO_CYC = cyc(FAST ? 600 : 4000);
  localparam integer BUF_CYC = cyc(FAST ? 1300 : 4700);
  localparam integer TIMEOUT_CYC = CLK_KHZ * TIMEOUT_US / 1000;
  localparam integer CW = $clog2(TIMEOUT_CYC + 1);

  generate
    if (SCL_HZ > 400_000) begin : g_bad_scl
      i2c_master_SCL_HZ_above_400kHz_is_not_supported bad ();
    end
    if (HOLD_CYC + 2 > LOW_CYC || HIGH_CYC < 3) begin : g_bad_clk
      i2c_master_CLK_HZ_too_low_for_SCL_HZ bad ();
    end
    if (TIMEOUT_CYC <= LOW_CYC + HIGH_CYC + BUF_CYC) begin : g_bad_timeout
      i2c_master_TIMEOUT_US_shorter_than_a_bit bad ();
    end
  endgenerate

  localparam integer M_HOLD = HOLD_CYC - 1, M_LOW = LOW_CYC - 1, M_HIGH = HIGH_CYC - 1,
                   M_SAMPLE = HIGH_CYC / 2, M_HD_STA = HD_STA_CYC - 1,
                   M_SU_STA = SU_STA_CYC - 1, M_SU_STO = SU_STO_CYC - 1, M_BUF = BUF_CYC - 1,
                   M_TIMEOUT = TIMEOUT_CYC - 1;
  localparam [CW-1:0] C_HOLD = M_HOLD[CW-1:0], C_LOW = M_LOW[CW-1:0],
                      C_HIGH = M_HIGH[CW-1:0], C_SAMPLE = M_SAMPLE[CW-1:0],
                      C_HD_STA = M_HD_STA[CW-1:0], C_SU_STA = M_SU_STA[CW-1:0],
                      C_SU_STO = M_SU_STO[CW-1:0], C_BUF = M_BUF[CW-1:0],
                      C_TIMEOUT = M_TIMEOUT[CW-1:0];

  // 2-flop synchronisers
  reg [1:0] scl_sync, sda_sync;
  wire scl_s = scl_sync[1], sda_s = sda_sync[1];

  localparam [3:0] S_IDLE = 4'd0, S_STA_HOLD = 4'd1, S_LOW = 4'd2, S_WAIT_HIGH = 4'd3,
                   S_HIGH = 4'd4, S_SETUP = 4'd5, S_BUF = 4'd6, S_RESP = 4'd7;
  reg [3:0] state;
  reg [2:0] op;  // what the bit engine is doing (OP_*)
  reg [CW-1:0] cnt;
  reg [3:0] bitn;  // bit within the byte (8 = ACK slot) or recovery pulses
  reg [7:0] shreg;
  reg ack_out, sampled;

  assign cmd_ready = (state == S_IDLE) && !rsp_valid;

  // SDA during the LOW phase of bit `bitn` of the current operation: 1 pulls low.
  reg sda_pull;
  always @(*) begin
    case (op)
      OP_WRITE: sda_pull = (bitn < 4'd8) ? !shreg[7] : 1'b0;
      OP_READ:  sda_pull = (bitn == 4'd8) ? ack_out : 1'b0;
      OP_STOP:  sda_pull = 1'b1;
      default:  sda_pull = 1'b0;  // repeated START, recovery
    endcase
  end

  task respond(input [1:0] err);
    begin
      rsp_valid <= 1'b1;
      rsp_err <= err;
      state <= S_RESP;
    end
  endtask

  always @(posedge clk) begin
    if (rst) begin
      scl_sync <= 2'b11;
      sda_sync <= 2'b11;
      state <= S_IDLE;
      op <= OP_START;
      cnt <= {CW{1'b0}};
      bitn <= 4'd0;
      shreg <= 8'd0;
      ack_out <= 1'b0;
      sampled <= 1'b1;
      scl_oe <= 1'b0;
      sda_oe <= 1'b0;
      owned <= 1'b0;
      rsp_valid <= 1'b0;
      rsp_data <= 8'd0;
      rsp_nack <= 1'b0;
      rsp_err <= ERR_OK;
    end else begin
      scl_sync <= {scl_sync[0], scl_i};
      sda_sync <= {sda_sync[0], sda_i};
      cnt <= cnt + 1'b1;
      case (state)
        S_IDLE: begin
          cnt <= {CW{1'b0}};
          if (cmd_valid && cmd_ready) begin
            op <= cmd_op;
            shreg <= cmd_data;
            ack_out <= cmd_ack;
            bitn <= 4'd0;
            rsp_nack <= 1'b0;
            rsp_data <= 8'd0;
            case (cmd_op)
              OP_START:
                if (owned) state <= S_LOW;
                else if (!scl_s || !sda_s) respond(ERR_BUSY);
                else begin
                  sda_oe <= 1'b1;
                  state <= S_STA_HOLD;
                end
              OP_WRITE, OP_READ: state <= owned ? S_LOW : S_RESP;
              OP_STOP: if (owned) state <= S_LOW; else respond(ERR_OK);
              OP_RECOVER:
                if (!owned && sda_s && scl_s) respond(ERR_OK);
                else begin
                  scl_oe <= 1'b1;
                  owned <= 1'b1;
                  state <= S_LOW;
                end
              default: respond(ERR_OK);
            endcase
            if ((cmd_op == OP_WRITE || cmd_op == OP_READ) && !owned) begin
              rsp_valid <= 1'b1;  // nothing to do off the bus: a NACK
              rsp_nack <= 1'b1;
              rsp_err <= ERR_OK;
            end
          end
        end
        S_STA_HOLD:  // SDA low, SCL high: hold, then take SCL low
          if (cnt == C_HD_STA) begin
            scl_oe <= 1'b1;
            owned <= 1'b1;
            respond(ERR_OK);
          end
        S_LOW: begin
          scl_oe <= 1'b1;
          if (cnt == C_HOLD) sda_oe <= sda_pull;
          if (cnt == C_LOW) begin
            scl_oe <= 1'b0;
            cnt <= {CW{1'b0}};
            state <= S_WAIT_HIGH;
          end
        end
        S_WAIT_HIGH:  // released: wait while SCL rises or a target stretches it
          if (scl_s) begin
            cnt <= {CW{1'b0}};
            state <= (op == OP_START || op == OP_STOP) ? S_SETUP : S_HIGH;
          end else if (cnt == C_TIMEOUT) begin
            scl_oe <= 1'b0;
            sda_oe <= 1'b0;
            owned <= 1'b0;
            respond(ERR_TIMEOUT);
          end
        S_HIGH: begin
          if (cnt == C_SAMPLE) sampled <= sda_s;
          if (cnt == C_HIGH) begin
            scl_oe <= 1'b1;
            cnt <= {CW{1'b0}};
            bitn <= bitn + 4'd1;
            state <= S_LOW;
            if (op == OP_RECOVER) begin
              rsp_data <= {4'd0, bitn + 4'd1};
              if (sampled) begin
                op <= OP_STOP;  // SDA free: finish with a STOP
              end else if (bitn == 4'd8) begin
                scl_oe <= 1'b0;
                owned <= 1'b0;
                respond(ERR_STUCK);
              end
            end else if (bitn == 4'd8) begin
              if (op == OP_WRITE) rsp_nack <= sampled;
              respond(ERR_OK);
            end else begin
              shreg <= {shreg[6:0], sampled};
              if (op == OP_READ) rsp_data <= {shreg[6:0], sampled};
            end
          end
        end
        S_SETUP:  // SCL high: repeated START or STOP setup
          if (op == OP_START && cnt == C_SU_STA) begin
            sda_oe <= 1'b1;
            cnt <= {CW{1'b0}};
            state <= S_STA_HOLD;
          end else if (op == OP_STOP && cnt == C_SU_STO) begin
            sda_oe <= 1'b0;
            cnt <= {CW{1'b0}};
            sampled <= 1'b0;
            state <= S_BUF;
          end
        S_BUF:  // STOP sent: bus free time from SDA seen high (`sampled`
                // marks that); SDA kept low by someone: timeout
          if (!sampled) begin
            if (sda_s) begin
              sampled <= 1'b1;
              cnt <= {CW{1'b0}};
            end else if (cnt == C_TIMEOUT) begin
              owned <= 1'b0;
              respond(ERR_TIMEOUT);
            end
          end else if (cnt == C_BUF) begin
            owned <= 1'b0;
            respond(ERR_OK);
          end
        S_RESP:
          if (rsp_ready) begin
            rsp_valid <= 1'b0;
            state <= S_IDLE;
          end
        default: state <= S_IDLE;
      endcase
    end
  end
`ifdef FORMAL
  // Properties (tests/formal/i2c_master.sby). Inputs free: commands,
  // rsp_ready and both line levels (any target, stretching, holding SCL
  // or SDA low for ever) but for the wired AND (a line we pull reads low,
  // below); the first clock resets. The pins are pull-down enables only
  // (scl_oe, sda_oe; rtl/i2c_pads.v makes them open drain): nothing here
  // can drive a line high.
  reg f_past = 1'b0;
  always @(posedge clk) f_past <= 1'b1;
  always @(*) if (!f_past) assume (rst);
  always @(*) if (f_past) assume (!rst);

  // How long each state may last: cnt counts its clocks and the state ends
  // at its bound, so no state but IDLE and RESP (which wait for the user)
  // can hold: a stuck line ends in ERR_TIMEOUT within TIMEOUT_CYC clocks.
  localparam integer F_BUFW = (M_TIMEOUT > M_BUF) ? M_TIMEOUT : M_BUF;
  always @(*)
    if (f_past) begin
      assert (state <= S_RESP);
      if (state == S_STA_HOLD) assert (cnt <= C_HD_STA);
      if (state == S_LOW) assert (cnt <= C_LOW);
      if (state == S_WAIT_HIGH) assert (cnt <= C_TIMEOUT);
      if (state == S_HIGH) assert (cnt <= C_HIGH);
      if (state == S_SETUP) assert (op == OP_START ? cnt <= C_SU_STA : (op == OP_STOP && cnt <= C_SU_STO && sda_oe));
      if (state == S_WAIT_HIGH && op == OP_STOP) assert (sda_oe);
      if (state == S_LOW && op == OP_STOP && cnt > C_HOLD) assert (sda_oe);
      if (state == S_BUF) assert (32'(cnt) <= F_BUFW && (sampled ? cnt <= C_BUF : 1'b1));
      if (state == S_HIGH) assert (bitn <= 4'd8 && op != OP_START && op != OP_STOP);
      if (state == S_LOW || state == S_WAIT_HIGH) assert (bitn <= 4'd8 || (bitn == 4'd9 && op == OP_STOP));
      if (state == S_RESP) assert (rsp_valid);
      if (state == S_IDLE) assert (!scl_oe || owned);
      // SCL is only ours to hold while we own the bus.
      if (scl_oe) assert (owned);
      if (state == S_STA_HOLD) assert (sda_oe);
      if (state == S_BUF) assert (op == OP_STOP && !sda_oe);
      if (state == S_HIGH || state == S_WAIT_HIGH || state == S_SETUP || state == S_BUF) assert (!scl_oe);
      if (state == S_LOW || state == S_BUF || state == S_WAIT_HIGH || state == S_HIGH || state == S_SETUP)
        assert (owned);
      assert (rsp_valid == (state == S_RESP));
    end

  // SDA (our pull-down) changes only while we hold SCL low before and after
  // the change (never in the clock SCL is released), except for a
  // START (SDA taken low with SCL released: then the START hold follows)
  // and a STOP (SDA released with SCL released: then the bus-free wait),
  // and the release of both lines when another device held SCL low too
  // long (the timeout).
  always @(posedge clk)
    if (f_past && !$past(rst) && $past(sda_oe) != sda_oe && !($past(scl_oe) && scl_oe)) begin
      if (sda_oe) assert (state == S_STA_HOLD);
      else assert (state == S_BUF || (state == S_RESP && rsp_err == ERR_TIMEOUT));
    end
  // A transaction ends in a STOP or a reported error: the bus is given up
  // only with a response, OK only after the bus-free wait of a STOP.
  always @(posedge clk)
    if (f_past && !$past(rst) && $past(owned) && !owned) begin
      assert (state == S_RESP && rsp_valid && !scl_oe);
      if (rsp_err == ERR_OK) assert ($past(state) == S_BUF && !sda_oe);
    end
  // A response is held until taken.
  always @(posedge clk)
    if (f_past && !$past(rst) && $past(rsp_valid && !rsp_ready))
      assert (rsp_valid && $stable(rsp_data) && $stable(rsp_err) && $stable(rsp_nack));

  // The bus: each line reads as the wired AND of our pull-down and any
  // target's (free, stretching included): a line we pull reads low.
  always @(*) begin
    if (scl_oe) assume (!scl_i);
    if (sda_oe) assume (!sda_i);
  end

  // A START (SDA pulled with SCL released) is only the START command's;
  // off the bus and idle (also after a timeout) both lines are released.
  always @(*)
    if (f_past) begin
      if (state == S_STA_HOLD) assert (op == OP_START && !scl_oe);
      if (!owned) assert (!scl_oe && (!sda_oe || state == S_STA_HOLD));
      if ((state == S_IDLE || state == S_RESP) && owned) assert (scl_oe);
      if (rsp_valid && rsp_err == ERR_TIMEOUT) assert (!owned && !scl_oe && !sda_oe);
    end

  // A stuck bus, measured at the pins by counters of this monitor's own:
  // m_rel counts the clocks since we released SCL, m_low says SCL has read
  // low at every one of them (someone holds it); m_srel / m_slow the same
  // for SDA since our STOP released it (SCL released). Either run lasts at
  // most TIMEOUT_CYC clocks with the bus ours: then ERR_TIMEOUT, both
  // lines released, the bus given up.
  localparam integer MW = CW + 1;  // room for TIMEOUT_CYC and more
  localparam [MW-1:0] F_TO = TIMEOUT_CYC[MW-1:0], F_MSAT = {MW{1'b1}};
  reg m_scl = 1'b0, m_sda = 1'b0, m_low = 1'b0, m_slow = 1'b0, m_stop = 1'b0;
  reg [MW-1:0] m_rel = {MW{1'b0}}, m_srel = {MW{1'b0}};
  wire m_scl_rel = m_scl && !scl_oe && owned;
  wire m_sda_stop = m_sda && !sda_oe && !m_scl && !scl_oe && owned;
  wire [MW-1:0] m_relc = m_scl_rel ? {MW{1'b0}} : m_rel, m_srelc = m_sda_stop ? {MW{1'b0}} : m_srel;
  wire m_lowc = (m_scl_rel || m_low) && !scl_i && !scl_oe;
  wire m_stopc = (m_sda_stop || m_stop) && !sda_oe && !scl_oe;
  wire m_slowc = m_stopc && (m_sda_stop || m_slow) && !sda_i;
  always @(posedge clk) begin
    m_scl <= scl_oe;
    m_sda <= sda_oe;
    m_rel <= (m_relc == F_MSAT) ? m_relc : m_relc + 1'b1;
    m_srel <= (m_srelc == F_MSAT) ? m_srelc : m_srelc + 1'b1;
    m_low <= m_lowc && !rst;
    m_stop <= m_stopc && !rst;
    m_slow <= m_slowc && !rst;
  end
  // And no timeout before it: the clocks at the start of the run that read
  // low (m_lead), at least TIMEOUT_CYC - 2 (the synchroniser's lag) when
  // the timeout ends the bus.
  reg [MW-1:0] m_lead = {MW{1'b0}}, m_slead = {MW{1'b0}};
  wire [MW-1:0] m_leadc = m_lowc ? m_relc + 1'b1 : (m_scl_rel ? {MW{1'b0}} : m_lead);
  wire [MW-1:0] m_sleadc = m_slowc ? m_srelc + 1'b1 : (m_sda_stop ? {MW{1'b0}} : m_slead);
  always @(posedge clk) begin
    m_lead <= m_leadc;
    m_slead <= m_sleadc;
  end
  always @(posedge clk)
    if (f_past && !$past(rst) && $past(owned) && !owned && rsp_err == ERR_TIMEOUT) begin
      if ($past(m_stopc)) assert ({1'b0, $past(m_sleadc)} + 2'd2 >= {1'b0, F_TO});
      else assert (!$past(scl_oe) && {1'b0, $past(m_leadc)} + 2'd2 >= {1'b0, F_TO});
    end
  always @(*)
    if (f_past) begin
      // A run broken at the pins is still in the synchroniser.
      if (state == S_WAIT_HIGH && !m_lowc)
        assert ({1'b0, m_leadc} + 2'd2 == {2'b0, cnt} ? scl_sync[1] :
                {1'b0, m_leadc} + 2'd1 == {2'b0, cnt} ? scl_sync[0] :
                m_leadc == {1'b0, cnt} && scl_i);
      if (state == S_BUF && !sampled && !m_slowc)
        assert ({1'b0, m_sleadc} + 2'd2 == {2'b0, cnt} ? sda_sync[1] :
                {1'b0, m_sleadc} + 2'd1 == {2'b0, cnt} ? sda_sync[0] :
                m_sleadc == {1'b0, cnt} && sda_i);
      if (owned && m_lowc) assert (m_relc < F_TO);
      if (owned && m_slowc) assert (m_srelc < F_TO);
    end
  always @(posedge clk)
    if (f_past && !$past(rst) && $past(owned) && !owned && ($past(m_lowc) || $past(m_slowc)))
      assert (rsp_valid && rsp_err == ERR_TIMEOUT && !scl_oe && !sda_oe);
  // After a timeout's response is taken the master is idle: it takes the
  // next command.
  always @(posedge clk)
    if (f_past && !$past(rst) && $past(rsp_valid && rsp_ready && rsp_err == ERR_TIMEOUT))
      assert (cmd_ready && !owned && !scl_oe && !sda_oe);
  // For induction: the monitor's runs against the state's counter; the
  // data bit set from HOLD after SCL fell to the end of the bit.
  always @(*)
    if (f_past) begin
      if ((state == S_LOW && cnt > C_HOLD) || state == S_WAIT_HIGH || state == S_HIGH)
        assert (sda_oe == sda_pull);
      if (state == S_LOW && cnt >= 2) assert (scl_sync == 2'b00);
      if (state == S_WAIT_HIGH) assert (m_relc == {1'b0, cnt} && (!m_lowc || scl_sync == 2'b00));
      if (state == S_HIGH || state == S_SETUP || state == S_BUF) assert (!m_lowc);
      if (state == S_STA_HOLD && owned) assert (!m_lowc);
      if (state == S_BUF && !sampled) assert (m_stopc && m_srelc == {1'b0, cnt} && (!m_slowc || sda_sync == 2'b00));
      if (state == S_BUF && sampled) assert (!m_slowc);
      if (m_stopc && owned) assert (state == S_BUF);
    end

  always @(posedge clk)
    if (f_past) begin
      cover (state == S_RESP && rsp_err == ERR_TIMEOUT && $past(state) == S_WAIT_HIGH);  // SCL stuck
      cover (state == S_RESP && rsp_err == ERR_TIMEOUT && $past(state) == S_BUF);        // SDA stuck after STOP
      cover ($past(owned) && !owned && rsp_err == ERR_OK);                              // a STOP
      cover (rsp_valid && !rsp_ready && $past(rsp_valid && !rsp_ready));                  // a response waiting
      cover (state == S_STA_HOLD && $past(state) == S_SETUP);                           // a repeated START
      cover (state == S_STA_HOLD && $past(state) == S_IDLE);                            // a START
      cover (state == S_HIGH && $past(state == S_WAIT_HIGH && cnt >= 4));              // a stretched SCL, then the bit
      cover (rsp_valid && rsp_err == ERR_BUSY);                                         // a busy bus refused
      cover (owned && m_lowc && m_relc == F_TO - 1'b1);                                // SCL held low to the bound
      cover (owned && m_slowc && m_srelc == F_TO - 1'b1);                              // SDA held low to the bound
      cover ($past(rsp_valid && rsp_ready && rsp_err == ERR_TIMEOUT) && cmd_valid && cmd_ready);  // idle again
    end
`endif
endmodule
`default_nettype wire
