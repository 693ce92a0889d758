# Second parameter set of ghost_filter: 3x3, a lookback ring of 5 frames
# (not a power of two), 12-bit magnitudes and 24-bit values.
verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/ghost_filter.v
  TOP_MODULE ghost_filter PREFIX Vghost_filter_small
  VERILATOR_ARGS -Wno-fatal --x-assign unique --x-initial unique -O3
    -GR_MAX=3 -GC_MAX=3 -GL_MAX=5 -GMAG_W=12 -GTAX_W=24)
