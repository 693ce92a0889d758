# Extra parameter sets of adc_ad7476 (the default build is 12 MHz, 35 kSPS,
# 6 MHz SCLK, one channel):
#  fast: 40 MHz clock, 20 MHz SCLK, 1 MSPS, two channels (Pmod AD1).
#  badsclk, badrate: negative controls for the ADC model's timing checks.
#  adc_ad7476 refuses illegal timing at elaboration, so each is a legal
#  build run at a faster clock than it was built for (a wrong PLL setting):
#  badsclk: built for 40 MHz, 1 MSPS, SCLK_DIV 1; run at 48 MHz -> 24 MHz SCLK.
#  badrate: built for 20 MHz, PERIOD 34 (588 235 S/s), SCLK_DIV 1; run at
#  40 MHz -> 20 MHz SCLK (legal), 1.18 MSPS, tQUIET 3 clocks = 75 ns < 86 ns
#  and tACQ 6 clocks = 150 ns < 250 ns.
eskin_verilate(${exe} Vadc_ad7476_fast ${CMAKE_SOURCE_DIR}/rtl/adc_ad7476.v adc_ad7476
  -GCLK_HZ=40000000 -GSAMPLE_HZ=1000000 -GSCLK_DIV=1 -GNCH=2)
eskin_verilate(${exe} Vadc_ad7476_badsclk ${CMAKE_SOURCE_DIR}/rtl/adc_ad7476.v adc_ad7476
  -GCLK_HZ=40000000 -GSAMPLE_HZ=1000000 -GSCLK_DIV=1)
eskin_verilate(${exe} Vadc_ad7476_badrate ${CMAKE_SOURCE_DIR}/rtl/adc_ad7476.v adc_ad7476
  -GCLK_HZ=20000000 -GSAMPLE_HZ=588235 -GSCLK_DIV=1)
