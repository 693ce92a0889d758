# Second build of dtmf_top: a 16x16 skin (32 carriers planned on odd DFT bins
# 1..63 of a 128-sample window at 35 kHz: inc = bin << 25), neurons and
# taxels every STEP = 16 samples (dt = 16/35 ms: the taxel stage needs
# 256 x 18 cycles per step, see docs/fpga.md), packets every 8 steps, a
# 32-token frame buffer between the DFT and the magnitudes (32 x 26 cycles
# of magnitudes would otherwise hold the DFT for more than a sample).
# Neuron constants: hls::make_izhikevich_config(RA, 16/35 ms, 10/32768, 1);
# TAX_RECIP = round(2^27 / (64 * full carrier 155.15 LSB)). The system test
# derives both from the scene and compares packets, so a wrong value here
# fails it.
verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v
  TOP_MODULE dtmf_top PREFIX Vdtmf_top_s16
  VERILATOR_ARGS -y ${CMAKE_SOURCE_DIR}/rtl -Wno-fatal --x-assign unique --x-initial unique -O3
    -GR=16 -GC=16 -GN=128 -GACC_W=20 -GSTEP=16 -GTOKEN_FIFO=32 -GDECIM_AMP=16'd8 -GDECIM_TAX=16'd8 -GTAX_RECIP=13517
    -GCARRIER_INC=1024'h7e0000007a00000076000000720000006e0000006a00000066000000620000005e0000005a00000056000000520000004e0000004a00000046000000420000003e0000003a00000036000000320000002e0000002a00000026000000220000001e0000001a00000016000000120000000e0000000a0000000600000002000000
    -GU_FRAC=23 -GC_CONST=-30222956 -GS2=12 -GS3=9 -GS4=21 -GGAIN_SHIFT=1)
# Third build: the default 3x3 top with CARRIER_CMD = 1 (SET_CARRIER_INC
# reloads the DFT carriers; too big for the UP5K next to everything else).
verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v
  TOP_MODULE dtmf_top PREFIX Vdtmf_top_cc
  VERILATOR_ARGS -y ${CMAKE_SOURCE_DIR}/rtl -Wno-fatal --x-assign unique --x-initial unique -O3
    -GCARRIER_CMD=1)
