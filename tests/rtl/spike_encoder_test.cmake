# Builds of spike_encoder for tests/rtl/spike_encoder_test.cpp (each also
# linted): 256 events a window (the default skins') and 4096 (a 64x64
# skin's layer).
set(eskin_default_args -GMAX=256)
eskin_verilate(${exe} Vspike_encoder_4096 ${CMAKE_SOURCE_DIR}/rtl/spike_encoder.v
  spike_encoder -GMAX=4096)
