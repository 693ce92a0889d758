# Second parameter set of uart_rx: 48 MHz / 115200 baud, CPB = 417.
eskin_verilate(${exe} Vuart_rx_slow ${CMAKE_SOURCE_DIR}/rtl/uart_rx.v uart_rx
  -GCLK_HZ=48000000 -GBAUD=115200)
