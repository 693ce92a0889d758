# Single-measurement build of the sequencer bench (BURST 0, conversion wait
# CONV_CYC = 2053 us * 12 MHz * 1.2 for the oscillator's spread).
verilate(${exe} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/mlx90393_sequencer_tb.v
  TOP_MODULE mlx90393_sequencer_tb PREFIX Vmlx90393_sequencer_tb_single
  VERILATOR_ARGS -y ${CMAKE_SOURCE_DIR}/rtl -Wno-fatal --x-assign unique
    --x-initial unique -O3 -GBURST=0)
add_test(NAME lint.mlx90393_sequencer.single
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module mlx90393_sequencer_tb
    -GBURST=0 ${CMAKE_CURRENT_SOURCE_DIR}/mlx90393_sequencer_tb.v)
set_tests_properties(lint.mlx90393_sequencer.single PROPERTIES LABELS lint)
