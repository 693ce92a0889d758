# link_framer behind uart_tx, decoded from the serial line.
verilate(${exe} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/link_framer_uart_tb.v
  TOP_MODULE link_framer_uart_tb PREFIX Vlink_framer_uart_tb
  VERILATOR_ARGS -y ${CMAKE_SOURCE_DIR}/rtl -Wno-fatal --x-assign unique
    --x-initial unique -O3)
