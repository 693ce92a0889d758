# Second parameter set of uart_tx: 48 MHz / 115200 baud, CPB = 417 (odd,
# not a power of two, baud error -0.08%).
verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/uart_tx.v
  TOP_MODULE uart_tx PREFIX Vuart_tx_slow
  VERILATOR_ARGS -Wno-fatal --x-assign unique --x-initial unique -O3
    -GCLK_HZ=48000000 -GBAUD=115200)
