# A 16-byte build, so that the test fills it (the top uses 512).
eskin_verilate(${exe} Vbyte_fifo_small ${CMAKE_SOURCE_DIR}/rtl/byte_fifo.v byte_fifo -GDEPTH=16)
