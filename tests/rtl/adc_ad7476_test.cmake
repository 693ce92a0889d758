# Extra parameter sets of adc_ad7476 (the default build is 12 MHz, 35 kSPS,
# 6 MHz SCLK, one channel):
#  fast: 40 MHz clock, 20 MHz SCLK, 1 MSPS, two channels (Pmod AD1).
#  badsclk: 48 MHz clock, SCLK_DIV 1 -> 24 MHz SCLK (negative control).
#  badrate: 40 MHz, 20 MHz SCLK, 1.2 MSPS -> tQUIET/tACQ too short (negative).
eskin_verilate(${exe} Vadc_ad7476_fast ${CMAKE_SOURCE_DIR}/rtl/adc_ad7476.v adc_ad7476
  -GCLK_HZ=40000000 -GSAMPLE_HZ=1000000 -GSCLK_DIV=1 -GNCH=2)
eskin_verilate(${exe} Vadc_ad7476_badsclk ${CMAKE_SOURCE_DIR}/rtl/adc_ad7476.v adc_ad7476
  -GCLK_HZ=48000000 -GSAMPLE_HZ=1000000 -GSCLK_DIV=1)
eskin_verilate(${exe} Vadc_ad7476_badrate ${CMAKE_SOURCE_DIR}/rtl/adc_ad7476.v adc_ad7476
  -GCLK_HZ=40000000 -GSAMPLE_HZ=1200000 -GSCLK_DIV=1)
