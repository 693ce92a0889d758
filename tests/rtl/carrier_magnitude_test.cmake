# Second parameter set of carrier_magnitude: odd ACC_W (split halves of
# unequal width) and a small SHIFT so that large sums saturate.
verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/carrier_magnitude.v
  TOP_MODULE carrier_magnitude PREFIX Vcarrier_magnitude_small
  VERILATOR_ARGS -Wno-fatal --x-assign unique --x-initial unique -O3
    -GACC_W=13 -GMAG_W=8 -GSHIFT=1)
