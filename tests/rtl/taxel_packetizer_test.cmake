# Builds of taxel_packetizer for tests/rtl/taxel_packetizer_test.cpp (each
# also linted): the default 3x3 skin and 64x64 (the ECP5-85F's streaming
# target).
set(eskin_default_args -GR=3 -GC=3)
eskin_verilate(${exe} Vtaxel_packetizer_64 ${CMAKE_SOURCE_DIR}/rtl/taxel_packetizer.v
  taxel_packetizer -GR=64 -GC=64)
