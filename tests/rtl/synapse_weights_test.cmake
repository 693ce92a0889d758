# Builds of synapse_weights for tests/rtl/synapse_weights_test.cpp (each also
# linted): the default 3x3 skin and 64x64 (the ECP5-85F's streaming target).
set(eskin_default_args -GR=3 -GC=3)
eskin_verilate(${exe} Vsynapse_weights_64 ${CMAKE_SOURCE_DIR}/rtl/synapse_weights.v
  synapse_weights -GR=64 -GC=64)
