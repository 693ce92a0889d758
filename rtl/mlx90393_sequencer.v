`default_nettype none
// mlx90393_sequencer: runs the MLX90393 sensors of one I2C bus through one
// i2c_master and emits one token per sensor per round:
// {id, t, x, y, z, flags} on a valid/ready stream.
//
// Sensors: NS of them; sensor k has the 7-bit address ADDR[7k +: 7] and sits
// directly on the bus (MUX_ADDR[7k +: 7] = 0) or behind channel
// MUX_CH[3k +: 3] of the TCA9548A at MUX_ADDR[7k +: 7]. Before talking to a
// sensor the sequencer selects its channel (and first deselects another mux's
// channel, so two same-address sensors are never joined); the TCA9548A
// applies a selection at the STOP that ends its write.
//
// Configuration: a sensor that is not configured (at start, after a NACK,
// after a reply that shows it lost its mode) gets EX, WR REG0/REG1/REG2
// (registers 0..2) and, in burst mode, SB with the XYZ axes; every status
// byte is checked (ERROR: it stays unconfigured and is tried again next
// round).
//
// Rounds:
//  BURST = 1: the sensors convert back to back; a round reads each sensor
//    once, in the order their DRDY (INT) pins rise. A sensor whose DRDY has
//    not risen STALE_CYC clocks into the round, or that is known missing, is
//    read anyway (it gives a MISSING or ERROR token), so a dead sensor costs
//    one short NACKed transaction per round and never stalls the bus.
//  BURST = 0: SM to every sensor, wait CONV_CYC clocks (the datasheet
//    conversion time with margin, computed by the generator), then RM each.
// Reading is RM|XYZ: status byte + 6 data bytes. The status must have ERROR
// clear, D1:D0 = 2 (6 bytes) and, in burst mode, the BURST bit set;
// otherwise the token carries no data and a flag:
//   flags[0..2] X/Y/Z code at the rail of its format (saturation)
//   flags[3] MISSING   the sensor NACKed (address or command)
//   flags[4] ERROR     status ERROR: sample dropped
//   flags[5] REPLY     unexpected D1:D0 count or mode bits: not trusted; or
//                      no measurement this round (the sensor was just
//                      configured, or its configuration was refused)
//   flags[6] BUS       bus timeout, or SDA stuck after recovery
//   flags[7] RECOVERED SDA was held low at a START and recovered (9 clocks)
// Counters (saturating 16 bit): nacks, status_errors, reply_errors,
// recoveries, bus_errors.
// t is the timestamp input when the reply's status byte arrived. In single
// mode a sensor that fails its SM is accounted then and gives its one token
// in the reading phase.
module mlx90393_sequencer #(
    parameter integer NS = 2,
    parameter [NS*7-1:0] ADDR = {7'h0D, 7'h0C},
    parameter [NS*7-1:0] MUX_ADDR = {NS{7'h00}},
    parameter [NS*3-1:0] MUX_CH = {NS{3'd0}},
    parameter [7:0] ID_BASE = 8'd0,
    parameter [15:0] REG0 = 16'h007C,  // HALLCONF 0xC, GAIN_SEL 7
    parameter [15:0] REG1 = 16'hE000,  // I2C only, INT pin = DRDY
    parameter [15:0] REG2 = 16'h0008,  // OSR 0, DIG_FILT 2, RES 0
    parameter integer BURST = 1,
    parameter integer CONV_CYC = 30_000,
    parameter integer STALE_CYC = 40_000
) (
    input  wire        clk,
    input  wire        rst,
    input  wire [NS-1:0] drdy,
    input  wire [31:0] tstamp,
    // i2c_master command/response
    output reg         m_cmd_valid,
    input  wire        m_cmd_ready,
    output reg  [2:0]  m_cmd_op,
    output reg  [7:0]  m_cmd_data,
    output reg         m_cmd_ack,
    input  wire        m_rsp_valid,
    output wire        m_rsp_ready,
    input  wire [7:0]  m_rsp_data,
    input  wire        m_rsp_nack,
    input  wire [1:0]  m_rsp_err,
    // tokens
    output reg         s_valid,
    input  wire        s_ready,
    output reg  [7:0]  s_id,
    output reg  [31:0] s_t,
    output reg  [15:0] s_x,
    output reg  [15:0] s_y,
    output reg  [15:0] s_z,
    output reg  [7:0]  s_flags,
    // counters
    output reg  [15:0] nacks,
    output reg  [15:0] status_errors,
    output reg  [15:0] reply_errors,
    output reg  [15:0] recoveries,
    output reg  [15:0] bus_errors
);
  localparam [2:0] OP_START = 3'd0, OP_WRITE = 3'd1, OP_READ = 3'd2, OP_STOP = 3'd3,
                   OP_RECOVER = 3'd4;
  localparam [1:0] ERR_OK = 2'd0, ERR_BUSY = 2'd1;
  localparam [7:0] CMD_SB = 8'h1E, CMD_SM = 8'h3E, CMD_RM = 8'h4E, CMD_WR = 8'h60,
                   CMD_EX = 8'h80;
  localparam integer SW = (NS > 1) ? $clog2(NS) : 1;
  localparam integer TW = $clog2((BURST != 0 ? STALE_CYC : CONV_CYC) + 2);

  generate
    if (NS < 1 || NS > 64) begin : g_bad_ns
      mlx90393_sequencer_NS_must_be_1_to_64 bad ();
    end
  endgenerate

  // Saturation rails per axis from RES (REG2) and TCMP_EN (REG1): signed
  // int16 at RES 0/1, offset 0x8000 at RES 2 or with TCMP, 0x4000 (0..0x7FFF)
  // at RES 3.
  function [31:0] rails(input [1:0] res);  // {lo, hi}
    if (REG1[10] || res == 2'd2) rails = {16'h0000, 16'hFFFF};
    else if (res == 2'd3) rails = {16'h0000, 16'h7FFF};
    else rails = {16'h8000, 16'h7FFF};
  endfunction
  localparam [31:0] RAIL_X = rails(REG2[6:5]), RAIL_Y = rails(REG2[8:7]),
                    RAIL_Z = rails(REG2[10:9]);

  // ------------------------------------------------------------------
  // Transaction engine: START, addr+W, wlen bytes, [Sr, addr+R, rlen bytes],
  // STOP, as a sequence of i2c_master commands.
  reg        t_go, t_busy, t_clr;
  reg [6:0]  t_addr;
  reg [7:0]  t_w0, t_w1, t_w2, t_w3;
  reg [2:0]  t_wlen, t_rlen;
  reg [3:0]  t_step;
  reg        t_nack, t_bus, t_recovered, t_retried;
  reg [31:0] t_when;
  reg [7:0]  rb0, rb1, rb2, rb3, rb4, rb5, rb6;

  // The command of step t_step.
  reg [2:0] st_op;
  reg [7:0] st_data;
  reg       st_ack;
  wire [3:0] wl = {1'b0, t_wlen}, rl = {1'b0, t_rlen};
  always @(*) begin
    st_op = OP_STOP;
    st_data = 8'd0;
    st_ack = 1'b0;
    if (t_step == 4'd0) st_op = OP_START;
    else if (t_step == 4'd1) begin
      st_op = OP_WRITE;
      st_data = {t_addr, 1'b0};
    end else if (t_step < 4'd2 + wl) begin
      st_op = OP_WRITE;
      case (t_step - 4'd2)
        4'd0: st_data = t_w0;
        4'd1: st_data = t_w1;
        4'd2: st_data = t_w2;
        default: st_data = t_w3;
      endcase
    end else if (rl != 4'd0 && t_step == 4'd2 + wl) st_op = OP_START;
    else if (rl != 4'd0 && t_step == 4'd3 + wl) begin
      st_op = OP_WRITE;
      st_data = {t_addr, 1'b1};
    end else if (rl != 4'd0 && t_step < 4'd4 + wl + rl) begin
      st_op = OP_READ;
      st_ack = (t_step + 4'd1 < 4'd4 + wl + rl);
    end
  end
  wire st_last = (rl == 4'd0) ? (t_step == 4'd2 + wl) : (t_step == 4'd4 + wl + rl);

  reg t_wait;  // command issued, waiting for its response
  assign m_rsp_ready = 1'b1;

  always @(posedge clk) begin
    if (rst) begin
      t_busy <= 1'b0;
      t_wait <= 1'b0;
      t_step <= 4'd0;
      m_cmd_valid <= 1'b0;
      m_cmd_op <= OP_START;
      m_cmd_data <= 8'd0;
      m_cmd_ack <= 1'b0;
      t_nack <= 1'b0;
      t_bus <= 1'b0;
      t_recovered <= 1'b0;
      t_retried <= 1'b0;
      t_when <= 32'd0;
      {rb0, rb1, rb2, rb3, rb4, rb5, rb6} <= 56'd0;
    end else begin
      if (m_cmd_valid && m_cmd_ready) m_cmd_valid <= 1'b0;
      if (t_clr) t_recovered <= 1'b0;  // sticky over a sensor's transactions
      if (t_go && !t_busy) begin
        t_busy <= 1'b1;
        t_step <= 4'd0;
        t_nack <= 1'b0;
        t_bus <= 1'b0;
        t_retried <= 1'b0;
      end else if (t_busy && !t_wait && !m_cmd_valid) begin
        m_cmd_valid <= 1'b1;
        m_cmd_op <= st_op;
        m_cmd_data <= st_data;
        m_cmd_ack <= st_ack;
        t_wait <= 1'b1;
      end else if (t_wait && m_rsp_valid) begin
        t_wait <= 1'b0;
        if (m_cmd_op == OP_RECOVER) begin
          // recovered (or not): retry the START once
          if (m_rsp_err != ERR_OK) begin
            t_bus <= 1'b1;
            t_busy <= 1'b0;
          end
        end else if (m_cmd_op == OP_START && m_rsp_err == ERR_BUSY && !t_retried) begin
          t_retried <= 1'b1;
          t_recovered <= 1'b1;
          m_cmd_valid <= 1'b1;  // clock out the stuck SDA, then retry
          m_cmd_op <= OP_RECOVER;
          t_wait <= 1'b1;
        end else if (m_rsp_err != ERR_OK) begin
          t_bus <= 1'b1;  // timeout, or still busy after recovery
          t_busy <= 1'b0;
        end else if (m_cmd_op == OP_WRITE && m_rsp_nack) begin
          t_nack <= 1'b1;
          t_step <= (rl == 4'd0) ? 4'd2 + wl : 4'd4 + wl + rl;  // go to STOP
        end else if (st_last) begin
          t_busy <= 1'b0;
        end else begin
          if (m_cmd_op == OP_READ) begin
            if (t_step == 4'd4 + wl) t_when <= tstamp;
            {rb0, rb1, rb2, rb3, rb4, rb5} <= {rb1, rb2, rb3, rb4, rb5, rb6};
            rb6 <= m_rsp_data;
          end
          t_step <= t_step + 4'd1;
        end
      end
    end
  end
  // Read bytes end up right-aligned in rb0..rb6: a 7-byte read leaves the
  // status in rb0, a 1-byte read leaves it in rb6.

  // ------------------------------------------------------------------
  // Control: configuration, rounds, tokens.
  localparam [3:0] C_ROUND = 4'd0, C_PICK = 4'd1, C_MUX_OFF = 4'd2, C_MUX_ON = 4'd3,
                   C_CFG = 4'd4, C_START_SM = 4'd5, C_WAIT_CONV = 4'd6, C_READ = 4'd7,
                   C_TOKEN = 4'd8, C_XACT = 4'd9, C_MUX_CHK = 4'd10;
  reg [3:0] cstate, after_xact, mux_next;
  reg [SW-1:0] cur;
  reg [NS-1:0] pending, configured, missing;
  reg [2:0] cfg_step;  // EX, WR0, WR1, WR2, SB
  reg [6:0] mux_now;   // selected mux (0: none)
  reg [2:0] ch_now;
  reg [TW-1:0] timer;
  reg sm_phase;        // single mode: 1 while issuing SM, 0 while reading
  reg did_read;        // this visit read a measurement (RM)
  reg [NS-1:0] drdy_a, drdy_b;

  wire [6:0] k_addr = ADDR[cur*7 +: 7];
  wire [6:0] k_mux = MUX_ADDR[cur*7 +: 7];
  wire [2:0] k_ch = MUX_CH[cur*3 +: 3];
  wire stale = (BURST != 0) && (timer >= STALE_CYC[TW-1:0]);

  // Pick the next pending sensor: burst mode, the lowest-numbered one whose
  // DRDY is high, or any known-missing one, or (when stale) any.
  reg found;
  reg [SW-1:0] pick;
  integer i;
  always @(*) begin
    found = 1'b0;
    pick = {SW{1'b0}};
    for (i = NS - 1; i >= 0; i = i - 1)
      if (pending[i] && (BURST == 0 || drdy_b[i] || missing[i] || !configured[i] || stale)) begin
        found = 1'b1;
        pick = i[SW-1:0];
      end
  end

  function [15:0] inc16(input [15:0] v);
    inc16 = (v == 16'hFFFF) ? v : v + 16'd1;
  endfunction

  // Status byte of a 7-byte RM reply: ERROR bit 4, BURST bit 7, D1:D0.
  wire st_error = rb0[4], st_burst = rb0[7];
  wire unused_status = &{1'b0, rb0[6:5], rb0[3:2]};  // WOC, SM, SED, RS: not needed
  wire reply_ok = (rb0[1:0] == 2'd2) && (BURST == 0 || st_burst);
  wire [15:0] vx = {rb1, rb2}, vy = {rb3, rb4}, vz = {rb5, rb6};

  task xact(input [6:0] a, input [7:0] w0, input [7:0] w1, input [7:0] w2, input [7:0] w3,
            input [2:0] wlen, input [2:0] rlen, input [3:0] then);
    begin
      t_addr <= a;
      t_w0 <= w0;
      t_w1 <= w1;
      t_w2 <= w2;
      t_w3 <= w3;
      t_wlen <= wlen;
      t_rlen <= rlen;
      t_go <= 1'b1;
      after_xact <= then;
      cstate <= C_XACT;
    end
  endtask

  always @(posedge clk) begin
    if (rst) begin
      cstate <= C_ROUND;
      after_xact <= C_ROUND;
      cur <= {SW{1'b0}};
      pending <= {NS{1'b0}};
      configured <= {NS{1'b0}};
      missing <= {NS{1'b0}};
      cfg_step <= 3'd0;
      mux_now <= 7'd0;
      ch_now <= 3'd0;
      timer <= {TW{1'b0}};
      sm_phase <= 1'b0;
      did_read <= 1'b0;
      t_go <= 1'b0;
      t_clr <= 1'b0;
      mux_next <= C_CFG;
      t_addr <= 7'd0;
      {t_w0, t_w1, t_w2, t_w3} <= 32'd0;
      t_wlen <= 3'd0;
      t_rlen <= 3'd0;
      drdy_a <= {NS{1'b0}};
      drdy_b <= {NS{1'b0}};
      s_valid <= 1'b0;
      s_id <= 8'd0;
      s_t <= 32'd0;
      {s_x, s_y, s_z} <= 48'd0;
      s_flags <= 8'd0;
      {nacks, status_errors, reply_errors, recoveries, bus_errors} <= 80'd0;
    end else begin
      drdy_a <= drdy;
      drdy_b <= drdy_a;
      t_go <= 1'b0;
      t_clr <= 1'b0;
      if (timer != {TW{1'b1}}) timer <= timer + 1'b1;
      if (s_valid && s_ready) s_valid <= 1'b0;
      case (cstate)
        C_ROUND: begin  // a new round: every sensor pending
          pending <= {NS{1'b1}};
          timer <= {TW{1'b0}};
          sm_phase <= (BURST == 0);
          cstate <= C_PICK;
        end
        C_PICK:
          if (pending == {NS{1'b0}}) begin
            if (sm_phase) begin  // single mode: all SM sent, wait the conversion
              sm_phase <= 1'b0;
              pending <= {NS{1'b1}};
              timer <= {TW{1'b0}};
              cstate <= C_WAIT_CONV;
            end else begin
              cstate <= C_ROUND;
            end
          end else if (found) begin
            cur <= pick;
            cstate <= C_MUX_OFF;
          end
        C_MUX_OFF:  // another mux has a channel on: switch it off first
          if (mux_now != 7'd0 && mux_now != k_mux) begin
            mux_now <= 7'd0;
            mux_next <= C_MUX_ON;
            xact(mux_now, 8'h00, 8'd0, 8'd0, 8'd0, 3'd1, 3'd0, C_MUX_CHK);
          end else begin
            cstate <= C_MUX_ON;
          end
        C_MUX_ON:
          if (k_mux != 7'd0 && (mux_now != k_mux || ch_now != k_ch)) begin
            mux_now <= k_mux;
            ch_now <= k_ch;
            mux_next <= C_CFG;
            xact(k_mux, 8'd1 << k_ch, 8'd0, 8'd0, 8'd0, 3'd1, 3'd0, C_MUX_CHK);
          end else begin
            cstate <= C_CFG;
          end
        C_CFG:
          if (configured[cur]) begin
            cstate <= sm_phase ? C_START_SM : C_READ;
          end else if (cfg_step != 3'd0 && (t_nack || t_bus || rb6[4])) begin
            cfg_step <= 3'd0;  // the last step failed: try again next round
            cstate <= C_TOKEN;
          end else if (cfg_step == ((BURST != 0) ? 3'd5 : 3'd4)) begin
            cfg_step <= 3'd0;
            configured[cur] <= 1'b1;
            missing[cur] <= 1'b0;
            // single mode: on with SM; burst: the first data come next round
            cstate <= sm_phase ? C_START_SM : C_TOKEN;
          end else begin
            case (cfg_step)
              3'd0: xact(k_addr, CMD_EX, 8'd0, 8'd0, 8'd0, 3'd1, 3'd1, C_CFG);
              3'd1: xact(k_addr, CMD_WR, REG0[15:8], REG0[7:0], 8'h00, 3'd4, 3'd1, C_CFG);
              3'd2: xact(k_addr, CMD_WR, REG1[15:8], REG1[7:0], 8'h04, 3'd4, 3'd1, C_CFG);
              3'd3: xact(k_addr, CMD_WR, REG2[15:8], REG2[7:0], 8'h08, 3'd4, 3'd1, C_CFG);
              default: xact(k_addr, CMD_SB, 8'd0, 8'd0, 8'd0, 3'd1, 3'd1, C_CFG);
            endcase
            cfg_step <= cfg_step + 3'd1;
          end
        C_MUX_CHK:  // a mux write failed: its state is unknown, the sensor unreachable
          if (t_nack || t_bus) begin
            mux_now <= 7'd0;
            cstate <= C_TOKEN;
          end else begin
            cstate <= mux_next;
          end
        C_START_SM:
          xact(k_addr, CMD_SM, 8'd0, 8'd0, 8'd0, 3'd1, 3'd1, C_TOKEN);
        C_WAIT_CONV:
          if (timer >= CONV_CYC[TW-1:0]) cstate <= C_PICK;
        C_READ: begin
          did_read <= 1'b1;
          xact(k_addr, CMD_RM, 8'd0, 8'd0, 8'd0, 3'd1, 3'd7, C_TOKEN);
        end
        C_XACT:
          if (!t_go && !t_busy) cstate <= after_xact;
        C_TOKEN:  // sensor `cur` is done for this phase: account, emit a token
          if (!(s_valid && !s_ready)) begin
            pending[cur] <= 1'b0;
            did_read <= 1'b0;
            t_clr <= 1'b1;
            cstate <= C_PICK;
            if (t_recovered) recoveries <= inc16(recoveries);
            if (t_bus) bus_errors <= inc16(bus_errors);
            if (t_nack) begin
              nacks <= inc16(nacks);
              missing[cur] <= 1'b1;
              configured[cur] <= 1'b0;
            end
            if (sm_phase && !t_nack && !t_bus && configured[cur] && rb6[4]) begin
              configured[cur] <= 1'b0;  // SM refused: reconfigure next round
              status_errors <= inc16(status_errors);
            end
            if (!sm_phase) begin  // reading phase: exactly one token
              s_valid <= 1'b1;
              s_id <= ID_BASE + {{(8 - SW) {1'b0}}, cur};
              s_t <= t_when;
              {s_x, s_y, s_z} <= 48'd0;
              s_flags <= {t_recovered, t_bus, !did_read && !t_nack && !t_bus, 1'b0, t_nack, 3'b000};
              if (did_read && !t_nack && !t_bus) begin
                if (st_error) begin
                  s_flags[4] <= 1'b1;
                  status_errors <= inc16(status_errors);
                end else if (!reply_ok) begin
                  s_flags[5] <= 1'b1;
                  reply_errors <= inc16(reply_errors);
                  if (BURST != 0 && !st_burst) configured[cur] <= 1'b0;
                end else begin
                  {s_x, s_y, s_z} <= {vx, vy, vz};
                  s_flags[0] <= (vx == RAIL_X[31:16]) || (vx == RAIL_X[15:0]);
                  s_flags[1] <= (vy == RAIL_Y[31:16]) || (vy == RAIL_Y[15:0]);
                  s_flags[2] <= (vz == RAIL_Z[31:16]) || (vz == RAIL_Z[15:0]);
                end
              end
            end
          end
        default: cstate <= C_ROUND;
      endcase
    end
  end
endmodule
`default_nettype wire
