# Single-measurement build of the sequencer bench (BURST 0, conversion wait
# CONV_CYC = 2053 us * 12 MHz * 1.2 for the oscillator's spread).
eskin_verilate(${exe} Vmlx90393_sequencer_tb_single
  ${CMAKE_CURRENT_SOURCE_DIR}/mlx90393_sequencer_tb.v mlx90393_sequencer_tb -GBURST=0)
