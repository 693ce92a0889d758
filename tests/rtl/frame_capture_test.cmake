# The default build is the 3x3 top's: KS 7, W 18, N 32, STEP 35 (the test's
# constants); a second parameter set is linted: 20 channels, N 64, STEP 70.
add_test(NAME lint.Vframe_capture_10x10
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module frame_capture
    ${CMAKE_SOURCE_DIR}/rtl/frame_capture.v -GKS=20 -GW=19 -GN=64 -GSTEP=70)
set_tests_properties(lint.Vframe_capture_10x10 PROPERTIES LABELS lint)
