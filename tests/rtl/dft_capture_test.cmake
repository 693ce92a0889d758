# Builds of tests/rtl/dft_capture_tb.v (sdft_lanes into frame_capture) for
# tests/rtl/dft_capture_test.cpp, each also linted:
#  default: 6 lanes, KS 24, N 64, ACC_W 19 (a 12x12 skin's DFT at 1 MS/s);
#  l1:      1 lane, KS 7, N 32, ACC_W 18 (the default 3x3 top's DFT);
#  s32:     11 lanes, KS 64, N 128, ACC_W 20, STEP 1000 (a 32x32 skin's DFT
#           at 1 MS/s: the fewest lanes whose skipped samples fit 40 clocks).
set(eskin_default_args -GKS=24 -GN=64 -GACC_W=19 -GSTEP=3 -GLANES=6)
eskin_verilate(${exe} Vdft_capture_tb_l1 ${CMAKE_CURRENT_SOURCE_DIR}/dft_capture_tb.v dft_capture_tb
  -GKS=7 -GN=32 -GACC_W=18 -GSTEP=3 -GLANES=1)
eskin_verilate(${exe} Vdft_capture_tb_s32 ${CMAKE_CURRENT_SOURCE_DIR}/dft_capture_tb.v dft_capture_tb
  -GKS=64 -GN=128 -GACC_W=20 -GSTEP=1000 -GLANES=11)
