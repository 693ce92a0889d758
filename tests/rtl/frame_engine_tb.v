// Test bench of rtl/frame_engine.v for tests/rtl/frame_engine_test.cpp:
// the core's parameters pass through; its architectural registers and the
// instruction retirement are brought out (hierarchical references), and a
// back door loads and reads IMEM, KROM and DMEM so that one Verilated model
// runs many generated programs. The defaults are the test's first parameter
// set: IW 9, DW 8 (EBR DMEM), KW 4 with KROM word k = 0x9e3779b9 (k + 1)
// mod 2^32 (the test holds the same words).
`default_nettype none

module frame_engine_tb #(
    parameter integer IW = 9,
    parameter integer DW = 8,
    parameter integer KW = 4,
    parameter UCODE_HEX = "",
    parameter [32*(1<<KW)-1:0] KROM_INIT = 512'he3779b90_454021d7_a708a81e_08d12e65_6a99b4ac_cc623af3_2e2ac13a_8ff34781_f1bbcdc8_5384540f_b54cda56_1715609d_78dde6e4_daa66d2b_3c6ef372_9e3779b9,
    parameter integer FAST_SHIFT = 0
) (
    input  wire        clk,
    input  wire        rst,
    output wire [15:0] io_raddr,
    output wire [15:0] io_waddr,
    output wire        io_re,
    input  wire [31:0] io_rdata,
    output wire        io_we,
    output wire [31:0] io_wdata,
    input  wire [15:0] events,
    // back door: at a rising edge with bd_we, mem[bd_addr] = bd_data where
    // mem is IMEM (bd_mem 0), KROM (1) or DMEM (2)
    input  wire        bd_we,
    input  wire [1:0]  bd_mem,
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0] bd_addr,        // the low IW / KW / DW bits are used
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [31:0] bd_data,
    output wire [31:0] bd_rdata,       // mem[bd_addr], combinational
    // state after the last rising edge
    output wire        retire,         // the instruction in B ends at the next edge
    output wire        a_go,           // a cycle A ends at the next edge
    output wire        dm_we,          // `st` writes DMEM at the next edge
    output wire [15:0] dm_addr,
    output wire [31:0] dm_data,
    output wire [IW-1:0] pc,
    output wire [47:0] acc,
    output wire [31:0] p,
    output wire [15:0] t,
    output wire [15:0] x1,
    output wire [15:0] x2,
    output wire [15:0] x3,
    output wire [IW-1:0] stk0,
    output wire [IW-1:0] stk1,
    output wire [31:0] stk_overflows   // calls that overflowed the return stack since reset
);
  frame_engine #(.IW(IW), .DW(DW), .KW(KW), .UCODE_HEX(UCODE_HEX), .KROM_INIT(KROM_INIT),
                 .FAST_SHIFT(FAST_SHIFT)) u (
      .clk(clk), .rst(rst), .io_raddr(io_raddr), .io_re(io_re), .io_waddr(io_waddr), .io_rdata(io_rdata),
      .io_we(io_we), .io_wdata(io_wdata), .events(events));

  always @(posedge clk) begin
    if (bd_we) begin
      case (bd_mem)
        2'd0: u.imem[bd_addr[IW-1:0]] <= bd_data;
        2'd1: u.krom[bd_addr[KW-1:0]] <= bd_data;
        default: u.dmem[bd_addr[DW-1:0]] <= bd_data;
      endcase
    end
  end

  assign bd_rdata = bd_mem == 2'd0 ? u.imem[bd_addr[IW-1:0]] :
                    bd_mem == 2'd1 ? u.krom[bd_addr[KW-1:0]] : u.dmem[bd_addr[DW-1:0]];
  assign retire = u.bact && u.done;
  assign a_go = u.a_go;
  assign dm_we = u.bact && u.u_st;
  assign dm_addr = u.eab;
  assign dm_data = u.acc[31:0];
  assign pc = u.pc;
  assign acc = u.acc;
  assign p = u.p;
  assign t = u.t;
  assign x1 = u.x1;
  assign x2 = u.x2;
  assign x3 = u.x3;
  assign stk_overflows = u.stk_overflows;
  assign stk0 = u.stk0;
  assign stk1 = u.stk1;
endmodule
`default_nettype wire
