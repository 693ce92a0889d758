# Second parameter set of taxel_reconstruct: 3x3, 10-bit magnitudes (a
# shorter square root) and 32-bit taxel values (the unshifted product fits).
verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/taxel_reconstruct.v
  TOP_MODULE taxel_reconstruct PREFIX Vtaxel_reconstruct_small
  VERILATOR_ARGS -Wno-fatal --x-assign unique --x-initial unique -O3
    -GR_MAX=3 -GC_MAX=3 -GMAG_W=10 -GTAX_W=32)
