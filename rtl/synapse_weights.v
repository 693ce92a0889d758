`default_nettype none
// synapse_weights: the streaming 3x3 synapse of hls/synapse_weights.h, one
// taxel a clock. In: layer 0's spike flags, row-major, R x C a frame, frame
// after frame (in_flag, valid/ready). Out: for each taxel (i, j) in the same
// order the weighted layer's input
//     x_ij = sum_{di, dj in -1..1} W[di+1][dj+1] * s(i+di, j+dj),
// s = 0 off the grid (the first and last row and column see zeros), as
// SynapseWeights::input (out_x, signed XW = 20 bits: |x| <= 9 * 2^15 <
// 2^19, exact), out_last on a frame's last taxel. w holds the nine int16
// weights, W index k = (di+1) * 3 + (dj+1) at w[16k +: 16]; each taxel's
// sum uses the weights of the clock its code enters the adders (hold them
// steady while a frame is in flight to get one table per frame).
//
// Line buffers: output (i, j) needs input (i+1, j+1) (rows below the last
// and columns right of the last excepted), so the output runs about a row
// and a column behind the input. The flags live in 4 rows x C one-bit RAMs
// (distributed RAM, a row slot per row, round robin): 3 rows for the
// neighbourhood being read and a fourth that the input fills meanwhile, so
// the input never waits for the output to turn a row's corner. This is what
// keeps one element a clock across row and frame boundaries, where a
// neighbourhood closes without more input: the last row's outputs need only
// the row itself, and they go out while the next frame's first row comes
// in. Reading: each step shifts the 3x3 window a column and reads column j
// + 1 (three flags, one per slot: rows i-1, i, i+1), as the microcode's
// rolling code does; column 0's three flags, which a row's first step needs
// as well, are kept in 4 flip-flops (one per slot) beside the RAM, so every
// step reads the RAM once.
//
// Flow control: D = inputs taken - outputs started (0 .. 2C+1). Output (i,
// j) starts when the inputs it needs are in, D > need(i, j): C + 1, at the
// last column C, in the last row 1, and 0 for the frame's last taxel. The
// input is taken while D <= 2C: the row slot it writes then belongs to a
// row no started or later output reads (it holds row r - 4 when row r
// comes in, and the outputs of row r - 3, its last reader, have started).
// in_ready depends on registers only.
//
// Latency: an output starts in the clock after the input it waits for was
// taken, and is on out_valid 2 clocks later (its code registered, then the
// row sums, then the total): out_valid rises 3 edges after the handshake
// edge of input (i+1, j+1) (or the output before it, one a clock). The
// three stages stall together while out_valid && !out_ready.
module synapse_weights #(
    parameter integer R = 3,   // rows: 1 .. 255 (SynapseWeightsConfig's u8)
    parameter integer C = 3    // columns: 1 .. 255
) (
    input  wire               clk,
    input  wire               rst,
    input  wire [143:0]       w,
    input  wire               in_valid,
    output wire               in_ready,
    input  wire               in_flag,
    output reg                out_valid,
    input  wire               out_ready,
    output reg  signed [19:0] out_x,
    output reg                out_last
);
  generate
    if (R < 1 || R > 255 || C < 1 || C > 255) begin : g_bad_params
      synapse_weights_illegal_parameters u_stop ();  // no such module: stops elaboration
    end
  endgenerate

  localparam integer CB = (C > 1) ? $clog2(C) : 1;    // column index bits
  localparam integer RB = (R > 1) ? $clog2(R) : 1;    // row index bits
  localparam integer DB = $clog2(2 * C + 2) + 1;      // D: 0 .. 2C + 1
  localparam [CB-1:0] C_LAST = CB'(C - 1);
  localparam [RB-1:0] R_LAST = RB'(R - 1);
  localparam [DB-1:0] D_CAP = DB'(2 * C);
  localparam [DB-1:0] NEED_ROW = DB'(C + 1), NEED_ROW_END = DB'(C);

  // ---------------- input side: a flag a clock into row slot in_slot ------
  reg [CB-1:0] in_col;
  reg [1:0]    in_slot;
  reg [DB-1:0] d;
  assign in_ready = d <= D_CAP;
  wire take = in_valid && in_ready;

  reg [3:0] col0;            // column 0's flag of each slot
  reg [3:0] rd_bits;         // column out_col + 1's flag of each slot
  reg [CB-1:0] rd_col;
  genvar s;
  generate
    for (s = 0; s < 4; s = s + 1) begin : g_slot
      reg mem [0:C-1];
      always @(posedge clk)
        if (take && in_slot == 2'(s)) mem[in_col] <= in_flag;
      always @(*) rd_bits[s] = mem[rd_col];
    end
  endgenerate

  always @(posedge clk) begin
    if (rst) begin
      in_col  <= {CB{1'b0}};
      in_slot <= 2'd0;
    end else if (take) begin
      if (in_col == C_LAST) begin
        in_col  <= {CB{1'b0}};
        in_slot <= in_slot + 2'd1;
      end else begin
        in_col <= in_col + 1'b1;
      end
    end
  end
  always @(posedge clk)
    if (take && in_col == {CB{1'b0}}) col0[in_slot] <= in_flag;

  // ---------------- output side: start taxel (out_row, out_col) ----------
  reg [RB-1:0] out_row;
  reg [CB-1:0] out_col;
  reg [1:0]    out_slot;  // row out_row's slot
  wire row_first = out_row == {RB{1'b0}}, row_last = out_row == R_LAST;
  wire col_first = out_col == {CB{1'b0}}, col_last = out_col == C_LAST;
  wire [DB-1:0] need = row_last ? (col_last ? {DB{1'b0}} : DB'(1))
                                : (col_last ? NEED_ROW_END : NEED_ROW);
  wire en = !out_valid || out_ready;  // the pipeline moves
  wire start = en && d > need;

  always @(*) rd_col = col_last ? {CB{1'b0}} : out_col + 1'b1;
  // A column's three flags {row i-1, i, i+1} from the slots' bits, the
  // rows off the grid masked.
  function automatic [2:0] column(input [3:0] bits, input [1:0] slot, input up, input down);
    column = {up & bits[slot - 2'd1], bits[slot], down & bits[slot + 2'd1]};
  endfunction
  wire [2:0] v_mid = column(col0, out_slot, !row_first, !row_last);
  wire [2:0] v_next = column(rd_bits, out_slot, !row_first, !row_last);
  reg  [2:0] win_l, win_m;  // columns j - 1 and j of the last start
  // This start's window: columns j - 1, j, j + 1 (zeros off the grid).
  wire [2:0] c_l = col_first ? 3'd0 : win_l;
  wire [2:0] c_m = col_first ? v_mid : win_m;
  wire [2:0] c_r = col_last ? 3'd0 : v_next;

  always @(posedge clk) begin
    if (rst) begin
      out_row  <= {RB{1'b0}};
      out_col  <= {CB{1'b0}};
      out_slot <= 2'd0;
      d        <= {DB{1'b0}};
    end else begin
      d <= d + DB'(take) - DB'(start);
      if (start) begin
        win_l <= c_m;
        win_m <= c_r;
        if (col_last) begin
          out_col <= {CB{1'b0}};
          out_row <= row_last ? {RB{1'b0}} : out_row + 1'b1;
          // The next frame's first row follows in the next slot too.
          out_slot <= out_slot + 2'd1;
        end else begin
          out_col <= out_col + 1'b1;
        end
      end
    end
  end

  // ---------------- sum: code -> row sums -> total ------------------------
  // flags[k] = s(i + di, j + dj) at k = (di+1) * 3 + (dj+1).
  reg        v1, v2, last1, last2;
  reg [8:0]  flags;
  reg signed [17:0] rsum0, rsum1, rsum2;  // row di = -1, 0, +1
  // Each weight sign-extended to a row sum's width, or 0 where no spike.
  wire signed [17:0] term [0:8];
  genvar k;
  generate
    for (k = 0; k < 9; k = k + 1) begin : g_term
      assign term[k] = flags[k] ? {{2{w[16 * k + 15]}}, w[16 * k +: 16]} : 18'sd0;
    end
  endgenerate
  wire signed [19:0] total = {{2{rsum0[17]}}, rsum0} + {{2{rsum1[17]}}, rsum1} +
                             {{2{rsum2[17]}}, rsum2};
  always @(posedge clk) begin
    if (rst) begin
      v1 <= 1'b0;
      v2 <= 1'b0;
      out_valid <= 1'b0;
    end else if (en) begin
      v1 <= start;
      v2 <= v1;
      out_valid <= v2;
    end
  end
  always @(posedge clk) begin
    if (en) begin
      flags <= {c_r[0], c_m[0], c_l[0], c_r[1], c_m[1], c_l[1], c_r[2], c_m[2], c_l[2]};
      last1 <= row_last && col_last;
      rsum0 <= term[0] + term[1] + term[2];
      rsum1 <= term[3] + term[4] + term[5];
      rsum2 <= term[6] + term[7] + term[8];
      last2 <= last1;
      out_x <= total;
      out_last <= last2;
    end
  end
endmodule
`default_nettype wire
