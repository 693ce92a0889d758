# Second parameter set for rtl_izhikevich_layer_test: RS, 3 neurons, dt = 1 ms,
# 1 mV/ms per input LSB (make_izhikevich_config(RS, 1.0, 1.0, 0); the test
# checks that the builder still gives exactly these values). RS at dt = 1 ms
# drives U into saturation (d / a = 400 > 256) under maximal input.
set(izh_alt N=3 V_INIT=-272629760 U_INIT=-54525952 V_RESET=-272629760 U_JUMP=33554432
    U_FRAC=22 C_CONST=-68157440 M2=20972 S2=11 M3=16777 S3=8 M4=20972 S4=20 GAIN=16384
    GAIN_SHIFT=-8 X_SHIFT=0)
set(izh_alt_args)
foreach(p ${izh_alt})
  list(APPEND izh_alt_args -G${p})
  target_compile_definitions(${exe} PRIVATE IZH_ALT_${p})
endforeach()
verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/izhikevich_layer.v TOP_MODULE izhikevich_layer
  PREFIX Vizhikevich_layer_alt
  VERILATOR_ARGS -Wno-fatal --x-assign unique --x-initial unique -O3 ${izh_alt_args})
