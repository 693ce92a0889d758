// The Izhikevich update's constant words, as hls::neuron_block
// (ucode/dtmf_engine_image.h) lays them out: 0 v_init, 1 u_init, 2 v_reset,
// 3 u_jump, 4 u_frac - 22, 5 C, 6 m2, 7 s2, 8 m3, 9 s3, 10 m4, 11 s4,
// 12 gain, 13 and 14 gain_shift's right and left parts, 15 x_shift, 16
// input_change; the counts' low 6 bits and the multipliers' low 16 are
// kept, input_change as any bit set. cfg_we writes word cfg_addr from
// cfg_data. One decoder for the units that take these words
// (rtl/izhikevich_pipe.v, rtl/izhikevich_layer.v); a module includes it
// inside its body, after the ports cfg_we, cfg_addr and cfg_data.
reg [31:0] c_vinit, c_uinit, c_vreset, c_ujump, c_const;
reg [15:0] c_m2, c_m3, c_m4, c_gain;
reg [5:0]  c_fu, c_s2, c_s3, c_s4, c_gsr, c_gsl, c_xsh;
reg        c_ic;
always @(posedge clk)
  if (rst) begin
    c_vinit <= 0; c_uinit <= 0; c_vreset <= 0; c_ujump <= 0; c_const <= 0;
    c_m2 <= 0; c_m3 <= 0; c_m4 <= 0; c_gain <= 0;
    c_fu <= 0; c_s2 <= 0; c_s3 <= 0; c_s4 <= 0; c_gsr <= 0; c_gsl <= 0; c_xsh <= 0;
    c_ic <= 0;
  end else if (cfg_we)
    case (cfg_addr)
      5'd0: c_vinit <= cfg_data;
      5'd1: c_uinit <= cfg_data;
      5'd2: c_vreset <= cfg_data;
      5'd3: c_ujump <= cfg_data;
      5'd4: c_fu <= cfg_data[5:0];
      5'd5: c_const <= cfg_data;
      5'd6: c_m2 <= cfg_data[15:0];
      5'd7: c_s2 <= cfg_data[5:0];
      5'd8: c_m3 <= cfg_data[15:0];
      5'd9: c_s3 <= cfg_data[5:0];
      5'd10: c_m4 <= cfg_data[15:0];
      5'd11: c_s4 <= cfg_data[5:0];
      5'd12: c_gain <= cfg_data[15:0];
      5'd13: c_gsr <= cfg_data[5:0];
      5'd14: c_gsl <= cfg_data[5:0];
      5'd15: c_xsh <= cfg_data[5:0];
      5'd16: c_ic <= |cfg_data;
      default: ;
    endcase
