# link_framer behind uart_tx, decoded from the serial line.
eskin_verilate(${exe} Vlink_framer_uart_tb ${CMAKE_CURRENT_SOURCE_DIR}/link_framer_uart_tb.v
  link_framer_uart_tb)
