# Builds of sdft_lanes for tests/rtl/sdft_lanes_test.cpp (each also linted):
#  default: 2 lanes, K_MAX 9, N 32, 12-bit samples, ACC_W 18 (a 4x4 skin's
#           DFT with demixing in dtmf_top);
#  l3:      3 lanes, K_MAX 13, N 48 (not a power of two), 12-bit samples and
#           coefficients, 8-bit table index, FB 2, ACC_W 21 (the narrowest);
#  l8:      8 lanes, K_MAX 20, N 64, ACC_W 20 (more lanes than 6: the merger,
#           not the lanes, sets the pace);
#  l1:      1 lane (sdft_bank's defaults): sdft_bank itself;
#  l32:     32 lanes, K_MAX 128, N 512, 12-bit samples, ACC_W 22 (a 64x64
#           skin's 128 bin-centred carriers at 1 MS/s).
set(eskin_default_args -GK_MAX=9 -GN=32 -GXW=12 -GACC_W=18 -GLANES=2)
eskin_verilate(${exe} Vsdft_lanes_l3 ${CMAKE_SOURCE_DIR}/rtl/sdft_lanes.v sdft_lanes
  -GK_MAX=13 -GN=48 -GXW=12 -GCW=12 -GTW=8 -GACC_W=21 -GFB=2 -GLANES=3)
eskin_verilate(${exe} Vsdft_lanes_l8 ${CMAKE_SOURCE_DIR}/rtl/sdft_lanes.v sdft_lanes
  -GK_MAX=20 -GN=64 -GXW=13 -GACC_W=20 -GLANES=8)
eskin_verilate(${exe} Vsdft_lanes_l1 ${CMAKE_SOURCE_DIR}/rtl/sdft_lanes.v sdft_lanes -GLANES=1)
eskin_verilate(${exe} Vsdft_lanes_l32 ${CMAKE_SOURCE_DIR}/rtl/sdft_lanes.v sdft_lanes
  -GK_MAX=128 -GN=512 -GXW=12 -GACC_W=22 -GLANES=32)
# 16 lanes of 3 channels, and the widest: 64 lanes of 2 (lint only).
add_test(NAME lint.Vsdft_lanes_l16
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module sdft_lanes
    -GK_MAX=40 -GLANES=16 ${CMAKE_SOURCE_DIR}/rtl/sdft_lanes.v)
add_test(NAME lint.Vsdft_lanes_l64
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module sdft_lanes
    -GK_MAX=128 -GN=512 -GXW=12 -GACC_W=22 -GLANES=64 ${CMAKE_SOURCE_DIR}/rtl/sdft_lanes.v)
set_tests_properties(lint.Vsdft_lanes_l16 lint.Vsdft_lanes_l64 PROPERTIES LABELS lint)
# sdft_bank without a window of its own (OWN_WIN 0: the lanes after lane 0
# read lane 0's) is clean on its own too; OWN_WIN is 0 or 1.
add_test(NAME lint.Vsdft_bank_shared_window
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module sdft_bank
    -GOWN_WIN=0 ${CMAKE_SOURCE_DIR}/rtl/sdft_bank.v)
add_test(NAME lint.sdft_bank_rejects_illegal_parameters_own_win
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module sdft_bank
    -GOWN_WIN=2 ${CMAKE_SOURCE_DIR}/rtl/sdft_bank.v)
set_tests_properties(lint.Vsdft_bank_shared_window lint.sdft_bank_rejects_illegal_parameters_own_win
  PROPERTIES LABELS lint)
set_tests_properties(lint.sdft_bank_rejects_illegal_parameters_own_win PROPERTIES
  PASS_REGULAR_EXPRESSION "sdft_bank_illegal_parameters")
