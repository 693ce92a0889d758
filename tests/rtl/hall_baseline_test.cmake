# Second parameter set of hall_baseline: 3 sensors from id 4, capture of 2,
# offset-binary codes (RES 2 / TCMP format).
eskin_verilate(${exe} Vhall_baseline_off ${CMAKE_SOURCE_DIR}/rtl/hall_baseline.v hall_baseline
  -GNS=3 -GID_BASE=4 -GCAPTURE_LOG2=1 -GOFFSET_X=16'h8000 -GOFFSET_Y=16'h8000 -GOFFSET_Z=16'h8000)
