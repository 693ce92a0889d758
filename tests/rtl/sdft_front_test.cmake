# Builds of tests/rtl/sdft_front_tb.v (sdft_front into frame_capture) for
# tests/rtl/sdft_front_test.cpp, each also linted:
#  default: a 64x64 skin's DFT at 1 MS/s: KS 128 (bin-centred carriers, no
#           DC channel), N 512, ACC_W 22, 32 lanes, a 4-sample FIFO, STEP 1000;
#  d0:      no FIFO (the ADC's register alone, as rtl/dtmf_top.v wires the
#           lanes today): KS 64, N 128, ACC_W 20, 16 lanes, STEP 1000.
set(eskin_default_args -GKS=128 -GN=512 -GACC_W=22 -GSTEP=1000 -GLANES=32 -GDEPTH=4)
eskin_verilate(${exe} Vsdft_front_tb_d0 ${CMAKE_CURRENT_SOURCE_DIR}/sdft_front_tb.v sdft_front_tb
  -GKS=64 -GN=128 -GACC_W=20 -GSTEP=1000 -GLANES=16 -GDEPTH=0)
# The module itself at the widest sets: 64 lanes with a 64-sample FIFO, and
# one lane with a one-sample FIFO (lint only).
add_test(NAME lint.Vsdft_front_l64_d64
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module sdft_front
    -GK_MAX=128 -GN=512 -GXW=12 -GACC_W=22 -GLANES=64 -GDEPTH=64 ${CMAKE_SOURCE_DIR}/rtl/sdft_front.v)
add_test(NAME lint.Vsdft_front_l1_d1
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module sdft_front
    -GLANES=1 -GDEPTH=1 ${CMAKE_SOURCE_DIR}/rtl/sdft_front.v)
set_tests_properties(lint.Vsdft_front_l64_d64 lint.Vsdft_front_l1_d1 PROPERTIES LABELS lint)
# Illegal sets stop at elaboration: a FIFO depth that is not a power of
# two, one beyond 64, and 65 lanes (sdft_lanes' stop, reached through the
# front end).
foreach(front_set "depth3|sdft_front|-GDEPTH=3" "depth128|sdft_front|-GDEPTH=128"
            "lanes65|sdft_lanes|-GK_MAX=128;-GN=512;-GXW=12;-GACC_W=22;-GLANES=65")
  # Names of their own: this file is included inside the loop over the
  # tests, whose `name` the default build still needs.
  string(REPLACE "|" ";" front_parts "${front_set}")
  list(GET front_parts 0 front_name)
  list(GET front_parts 1 front_stop)
  list(SUBLIST front_parts 2 -1 front_params)
  add_test(NAME lint.sdft_front_rejects_illegal_parameters_${front_name}
    COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module sdft_front
      ${front_params} ${CMAKE_SOURCE_DIR}/rtl/sdft_front.v)
  set_tests_properties(lint.sdft_front_rejects_illegal_parameters_${front_name} PROPERTIES
    LABELS lint PASS_REGULAR_EXPRESSION "${front_stop}_illegal_parameters")
endforeach()
