# Second parameter set of uart_tx: 48 MHz / 115200 baud, CPB = 417 (odd,
# not a power of two, baud error -0.08%).
eskin_verilate(${exe} Vuart_tx_slow ${CMAKE_SOURCE_DIR}/rtl/uart_tx.v uart_tx
  -GCLK_HZ=48000000 -GBAUD=115200)
