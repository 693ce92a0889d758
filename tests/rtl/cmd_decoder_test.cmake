# Second build: a 32-byte command FIFO, to drive the overflow path.
eskin_verilate(${exe} Vcmd_decoder_tb_small ${CMAKE_CURRENT_SOURCE_DIR}/cmd_decoder_tb.v
  cmd_decoder_tb -GDEPTH=32)
# The two decoders of rtl/mixed_top.v: the DTMF top's keeps every type but
# the Hall commands 0x90-0x9F, the Hall top's only those.
eskin_verilate(${exe} Vcmd_decoder_tb_dtmf ${CMAKE_CURRENT_SOURCE_DIR}/cmd_decoder_tb.v
  cmd_decoder_tb -GTYPE_LO=8'h90 -GTYPE_HI=8'h9f -GTYPE_IN=0)
eskin_verilate(${exe} Vcmd_decoder_tb_hall ${CMAKE_CURRENT_SOURCE_DIR}/cmd_decoder_tb.v
  cmd_decoder_tb -GTYPE_LO=8'h90 -GTYPE_HI=8'h9f -GTYPE_IN=1)
