# Second parameter set of uart_rx: 48 MHz / 115200 baud, CPB = 417.
verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/uart_rx.v
  TOP_MODULE uart_rx PREFIX Vuart_rx_slow
  VERILATOR_ARGS -Wno-fatal --x-assign unique --x-initial unique -O3
    -GCLK_HZ=48000000 -GBAUD=115200)
