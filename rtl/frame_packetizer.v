// frame_packetizer: turns the DTMF pipeline's token streams into host-link
// packet requests for rtl/link_framer.v (header, then payload bytes; packet
// layouts in host/link/link_decoder.h). The spec is hls/dtmf_chain.h.
//
// The pipeline never waits for the link: every input port is always ready.
// Frames are buffered in block RAM and sent while the pipeline runs on.
//   amplitudes (type 0x01): the magnitudes {k, mag} of every decim_amp-th
//     frame (frames counted from reset, frame 0 first), mag u16 LE in k
//     order; t = the frame's sample counter.
//   taxels dense (0x02): rows u8, cols u8, then every taxel value u16 LE in
//     arrival order (row-major), of every decim_tax-th taxel frame.
//   spikes (0x04): per window of decim_tax neuron steps (step 0 opens one),
//     the spike events {dt u16 = t_spike - t_window, layer u8 = 0, neuron u16}
//     in order; t = t_window, the t of the window's first step. A window
//     without spikes sends nothing. If the previous spike packet has not
//     been taken when a window closes, the window stays open (the next
//     packet covers both, dt from the older start): nothing is lost.
//   status (0x05): the 24-byte block from the top on `status_req` and, with
//     mask bit 3, every decim_status frames (frame 0 first); `samples` and t
//     = the top's sample count when the header is issued.
// mask: bit 0 amplitudes, 1 taxels, 2 spikes, 3 periodic status.
// Losses (counted in `dropped`, saturating): an amplitude or taxel frame
// selected while the previous one of its type is still unsent; a spike
// event arriving with the spike FIFO full.
// Send priority: status, amplitudes, taxels, spikes (one packet at a time).
module frame_packetizer #(
    parameter integer K_MAX = 6,        // carriers (amplitude buffer)
    parameter integer T_MAX = 9,        // taxels per frame (taxel buffer)
    parameter integer SPK_DEPTH = 512,  // spike event FIFO entries (power of 2)
    parameter integer MAG_W = 16,
    parameter integer TAX_W = 16,
    parameter integer K_W = 8,
    parameter integer DW = 10           // decimation counter width: decim < 2^DW
) (
    input  wire             clk,
    input  wire             rst,
    input  wire [3:0]       mask,
    input  wire [DW-1:0]    decim_amp,   // amplitude frames every decim_amp steps, >= 1
    input  wire [DW-1:0]    decim_tax,   // taxel frames and spike windows, >= 1
    input  wire [DW-1:0]    decim_status,// periodic status (mask bit 3), >= 1
    input  wire [7:0]       rows,
    input  wire [7:0]       cols,
    // magnitudes
    input  wire             amp_valid,
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [K_W-1:0]   amp_k,        // low KA bits used
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [MAG_W-1:0] amp_mag,
    input  wire             amp_last,
    input  wire [31:0]      amp_t,
    // taxels
    input  wire             tax_valid,
    input  wire [TAX_W-1:0] tax_value,
    input  wire             tax_last,
    input  wire [31:0]      tax_t,
    // neuron outputs (one per neuron per step)
    input  wire             nrn_valid,
    input  wire [15:0]      nrn_neuron,
    input  wire [31:0]      nrn_t,
    input  wire             nrn_spike,
    input  wire             nrn_last,
    // status
    input  wire             status_req,
    input  wire [159:0]     status_fixed, // status bytes 0..19
    input  wire [31:0]      samples,      // bytes 20..23
    output reg  [15:0]      dropped,
    // link_framer request
    output reg              hdr_valid,
    input  wire             hdr_ready,
    output reg  [7:0]       hdr_type,     // hdr_* valid with hdr_valid
    output reg  [31:0]      hdr_t,
    output reg  [15:0]      hdr_len,
    output reg              s_valid,
    input  wire             s_ready,
    output reg  [7:0]       s_data
);
  localparam integer KA = (K_MAX > 1) ? $clog2(K_MAX) : 1;
  localparam integer TA = (T_MAX > 1) ? $clog2(T_MAX) : 1;
  localparam integer SA = $clog2(SPK_DEPTH);
  localparam integer AMP_LEN_I = 2 * K_MAX;
  localparam [15:0] K16 = K_MAX[15:0];
  localparam [15:0] AMP_LEN = AMP_LEN_I[15:0];

  reg amp_done, tax_done, spk_done, status_done;  // packet sent (from the sender)

  // ---------------- frame selection and drop counting ----------------
  reg [DW-1:0] amp_cnt, tax_cnt, step_cnt, stat_cnt;
  // Down-counters: a frame is selected when its counter is 0, which then
  // reloads decim - 1 (so frame 0 is selected, then every decim-th).
  wire amp_sel = (amp_cnt == {DW{1'b0}});
  wire tax_sel = (tax_cnt == {DW{1'b0}});
  wire win_last = (step_cnt == {DW{1'b0}});  // the window's last step
  wire stat_sel = (stat_cnt == {DW{1'b0}});
  reg drop_amp, drop_tax, drop_spk;
  always @(posedge clk) begin
    if (rst) dropped <= 16'd0;
    else if ((drop_amp || drop_tax || drop_spk) && dropped != 16'hFFFF) dropped <= dropped + 16'd1;
  end

  // ---------------- amplitude buffer ----------------
  reg [MAG_W-1:0] amp_mem [0:(1 << KA)-1];
  reg amp_full, amp_wr;  // amp_wr: the frame being received is stored
  reg amp_first;         // next magnitude token opens a frame
  reg [31:0] amp_tq;
  wire amp_free = !amp_full || amp_done;  // the sender releases it this cycle
  wire amp_take = amp_valid && (amp_first ? (amp_sel && mask[0] && amp_free) : amp_wr);
  reg status_pend;
  always @(posedge clk) begin
    if (amp_take) amp_mem[amp_k[KA-1:0]] <= amp_mag;
  end
  always @(posedge clk) begin
    drop_amp <= 1'b0;
    if (rst) begin
      amp_cnt <= {DW{1'b0}}; stat_cnt <= {DW{1'b0}}; amp_full <= 1'b0; amp_wr <= 1'b0; amp_first <= 1'b1;
      amp_tq <= 32'd0; status_pend <= 1'b0;
    end else begin
      if (amp_done) amp_full <= 1'b0;
      if (status_done) status_pend <= 1'b0;
      if (status_req) status_pend <= 1'b1;
      if (amp_valid) begin
        if (amp_first) begin
          amp_wr <= amp_sel && mask[0] && amp_free;
          drop_amp <= amp_sel && mask[0] && !amp_free;
          if (stat_sel && mask[3]) status_pend <= 1'b1;
          stat_cnt <= stat_sel ? decim_status - 1'b1 : stat_cnt - 1'b1;
        end
        amp_first <= amp_last;
        if (amp_last) begin
          amp_cnt <= amp_sel ? decim_amp - 1'b1 : amp_cnt - 1'b1;
          if (amp_take) begin
            amp_full <= 1'b1;
            amp_tq <= amp_t;
          end
          amp_wr <= 1'b0;
        end
      end
    end
  end

  // ---------------- taxel buffer ----------------
  reg [TAX_W-1:0] tax_mem [0:(1 << TA)-1];
  reg tax_full, tax_wr, tax_first;
  reg [TA-1:0] tax_wa;
  reg [15:0] tax_n;      // taxels stored in the frame being sent
  reg [31:0] tax_tq;
  wire tax_free = !tax_full || tax_done;
  wire tax_take = tax_valid && (tax_first ? (tax_sel && mask[1] && tax_free) : tax_wr);
  always @(posedge clk) begin
    if (tax_take) tax_mem[tax_wa] <= tax_value;
  end
  always @(posedge clk) begin
    drop_tax <= 1'b0;
    if (rst) begin
      tax_cnt <= {DW{1'b0}}; tax_full <= 1'b0; tax_wr <= 1'b0; tax_first <= 1'b1;
      tax_wa <= {TA{1'b0}}; tax_n <= 16'd0; tax_tq <= 32'd0;
    end else begin
      if (tax_done) tax_full <= 1'b0;
      if (tax_valid) begin
        if (tax_first) begin
          tax_wr <= tax_sel && mask[1] && tax_free;
          drop_tax <= tax_sel && mask[1] && !tax_free;
        end
        tax_first <= tax_last;
        tax_wa <= tax_last ? {TA{1'b0}} : tax_wa + 1'b1;
        if (tax_last) begin
          tax_cnt <= tax_sel ? decim_tax - 1'b1 : tax_cnt - 1'b1;
          if (tax_take) begin
            tax_full <= 1'b1;
            tax_tq <= tax_t;
            tax_n <= {{(16 - TA){1'b0}}, tax_wa} + 16'd1;
          end
          tax_wr <= 1'b0;
        end
      end
    end
  end

  // ---------------- spike FIFO and windows ----------------
  reg [31:0] spk_mem [0:SPK_DEPTH-1];  // {neuron, dt}
  reg [SA:0] spk_wp, spk_rp, spk_close;  // write, read, end of closed events
  reg win_open, spk_req;
  reg [31:0] win_t, spk_tq;
  reg [15:0] spk_n;
  // dt is sent as u16: the low 16 bits of t - t_window.
  wire [15:0] nrn_dt = win_open ? nrn_t[15:0] - win_t[15:0] : 16'd0;
  wire spk_fifo_full = (spk_wp - spk_rp) == SPK_DEPTH[SA:0];
  wire spk_push = nrn_valid && nrn_spike && mask[2] && !spk_fifo_full;
  wire [SA:0] spk_wp_next = spk_wp + {{SA{1'b0}}, spk_push};
  wire win_end = nrn_valid && nrn_last && win_last;
  wire [SA:0] spk_pend = spk_wp_next - spk_close;
  always @(posedge clk) begin
    if (spk_push) spk_mem[spk_wp[SA-1:0]] <= {nrn_neuron, nrn_dt[15:0]};
  end
  always @(posedge clk) begin
    drop_spk <= 1'b0;
    if (rst) begin
      step_cnt <= decim_tax - 1'b1; spk_wp <= {(SA + 1){1'b0}}; spk_close <= {(SA + 1){1'b0}};
      win_open <= 1'b0; spk_req <= 1'b0; win_t <= 32'd0; spk_tq <= 32'd0; spk_n <= 16'd0;
    end else begin
      if (spk_done) spk_req <= 1'b0;
      spk_wp <= spk_wp_next;
      drop_spk <= nrn_valid && nrn_spike && mask[2] && spk_fifo_full;
      if (nrn_valid) begin
        if (!win_open) begin
          win_open <= 1'b1;
          win_t <= nrn_t;
        end
        if (nrn_last) step_cnt <= win_last ? decim_tax - 1'b1 : step_cnt - 1'b1;
        if (win_end) begin
          if (spk_pend == {(SA + 1){1'b0}}) begin
            win_open <= 1'b0;  // nothing to send
          end else if (!spk_req || spk_done) begin
            win_open <= 1'b0;
            spk_req <= 1'b1;
            spk_tq <= win_open ? win_t : nrn_t;
            spk_n <= {{(15 - SA){1'b0}}, spk_pend};
            spk_close <= spk_wp_next;
          end
        end
      end
    end
  end

  // ---------------- sender ----------------
  // The header fields are functions of the source being sent (the framer
  // takes them at the header handshake); payload bytes come straight from
  // the RAM output registers, whose address is stable while a word is sent.
  localparam [1:0] SRC_STATUS = 2'd0, SRC_AMP = 2'd1, SRC_TAX = 2'd2, SRC_SPK = 2'd3;
  localparam [1:0] S_IDLE = 2'd0, S_HDR = 2'd1, S_RD = 2'd2, S_BYTE = 2'd3;
  localparam integer WIW = SA + 1;  // word index: up to SPK_DEPTH events
  reg [1:0] state;
  reg [1:0] src;
  reg [WIW-1:0] wi;        // word index (taxels: word 0 is {rows, cols})
  reg [4:0] bi;            // byte index in the word
  reg [31:0] samples_q;
  reg [MAG_W-1:0] amp_rd;
  reg [TAX_W-1:0] tax_rd;
  reg [31:0] spk_rd;
  /* verilator lint_off UNUSEDSIGNAL */
  wire [WIW-1:0] wi_m1 = wi - 1'b1;
  /* verilator lint_on UNUSEDSIGNAL */
  always @(posedge clk) begin
    amp_rd <= amp_mem[wi[KA-1:0]];
    tax_rd <= tax_mem[wi_m1[TA-1:0]];
    spk_rd <= spk_mem[spk_rp[SA-1:0]];
  end
  // Status: 12 little-endian 16-bit words, word wi.
  wire [191:0] status_vec = {samples_q, status_fixed};
  wire [15:0] status_half = status_vec[16 * wi[3:0] +: 16];
  wire [15:0] half = (src == SRC_STATUS) ? status_half :
                     (src == SRC_AMP) ? {{(16 - MAG_W){1'b0}}, amp_rd} :
                     (wi == {WIW{1'b0}}) ? {cols, rows} : {{(16 - TAX_W){1'b0}}, tax_rd};
  always @(*) begin
    if (src == SRC_SPK) begin
        case (bi[2:0])
          3'd0: s_data = spk_rd[7:0];
          3'd1: s_data = spk_rd[15:8];
          3'd2: s_data = 8'd0;  // layer 0: the receptor layer
          3'd3: s_data = spk_rd[23:16];
          default: s_data = spk_rd[31:24];
        endcase
    end else begin
      s_data = bi[0] ? half[15:8] : half[7:0];
    end
  end
  always @(*) begin
    case (src)
      SRC_STATUS: begin hdr_type = 8'h05; hdr_t = samples_q; hdr_len = 16'd24; end
      SRC_AMP: begin hdr_type = 8'h01; hdr_t = amp_tq; hdr_len = AMP_LEN; end
      SRC_TAX: begin hdr_type = 8'h02; hdr_t = tax_tq; hdr_len = 16'd2 + {tax_n[14:0], 1'b0}; end
      default: begin hdr_type = 8'h04; hdr_t = spk_tq; hdr_len = {spk_n[13:0], 2'b00} + spk_n; end
    endcase
  end
  wire [15:0] wi16 = {{(16 - WIW){1'b0}}, wi};
  reg last_byte, last_word;
  always @(*) begin
    case (src)
      SRC_STATUS: begin last_byte = bi[0]; last_word = (wi16 == 16'd11); end
      SRC_AMP: begin last_byte = bi[0]; last_word = (wi16 == K16 - 16'd1); end
      SRC_TAX: begin last_byte = bi[0]; last_word = (wi16 == tax_n); end
      default: begin last_byte = (bi[2:0] == 3'd4); last_word = (wi16 == spk_n - 16'd1); end
    endcase
  end
  always @(posedge clk) begin
    amp_done <= 1'b0; tax_done <= 1'b0; spk_done <= 1'b0; status_done <= 1'b0;
    if (rst) begin
      state <= S_IDLE; src <= SRC_STATUS; hdr_valid <= 1'b0; s_valid <= 1'b0;
      wi <= {WIW{1'b0}}; bi <= 5'd0; samples_q <= 32'd0; spk_rp <= {(SA + 1){1'b0}};
    end else begin
      case (state)
        S_IDLE: begin
          wi <= {WIW{1'b0}};
          bi <= 5'd0;
          if (status_pend && !status_done) begin
            src <= SRC_STATUS; samples_q <= samples; hdr_valid <= 1'b1; state <= S_HDR;
          end else if (amp_full && !amp_done) begin
            src <= SRC_AMP; hdr_valid <= 1'b1; state <= S_HDR;
          end else if (tax_full && !tax_done) begin
            src <= SRC_TAX; hdr_valid <= 1'b1; state <= S_HDR;
          end else if (spk_req && !spk_done) begin
            src <= SRC_SPK; hdr_valid <= 1'b1; state <= S_HDR;
          end
        end
        S_HDR: if (hdr_ready) begin
          hdr_valid <= 1'b0;
          state <= S_RD;
        end
        S_RD: begin  // the word's address is on the RAMs this cycle
          s_valid <= 1'b1;
          state <= S_BYTE;
        end
        default: if (s_ready) begin  // S_BYTE
          if (!last_byte) begin
            bi <= bi + 5'd1;
          end else begin
            bi <= 5'd0;
            s_valid <= 1'b0;
            if (src == SRC_SPK) spk_rp <= spk_rp + 1'b1;
            if (!last_word) begin
              wi <= wi + 1'b1;
              state <= S_RD;
            end else begin
              state <= S_IDLE;
              case (src)
                SRC_AMP: amp_done <= 1'b1;
                SRC_TAX: tax_done <= 1'b1;
                SRC_SPK: spk_done <= 1'b1;
                default: status_done <= 1'b1;
              endcase
            end
          end
        end
      endcase
    end
  end
endmodule
