# Second build: a 32-byte command FIFO, to drive the overflow path.
eskin_verilate(${exe} Vcmd_decoder_tb_small ${CMAKE_CURRENT_SOURCE_DIR}/cmd_decoder_tb.v
  cmd_decoder_tb -GDEPTH=32)
