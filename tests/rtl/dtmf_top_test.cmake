# Builds of dtmf_top for tests/rtl/dtmf_top_test.cpp. The integer
# parameters are those common/eskin/dtmf_top_plan.h derives for the scene and clock
# (the test checks every one against the plan, so a stale value here fails
# it); the microcode and constants are written by the test itself into
# ${dtmf_dir} from the plan (ucode/dtmf_ucode.h) before the model is built.
#  default: scenes/neuroskin2.yaml at 18 MHz (the iCE40 UP5K build: 12 MHz
#           oscillator x 3/2 by the PLL);
#  s10:     scenes/staggered10x10.yaml at 96 MHz (100 taxels, two neuron
#           layers each: the engine needs ~45 000 clocks per 1 ms frame),
#           its 20 DFT channels in 3 lanes (rtl/sdft_lanes.v);
#  s10fast: the same scene at 48 MHz with the engine's barrel shifter
#           (ENGINE_FAST_SHIFT, the ECP5 builds'): ~35 000 clocks a frame,
#           where the bit-serial engine's ~59 000 would not fit 48 000;
#  s10unit: the same scene at 24 MHz with the barrel shifter and the
#           neuron unit (NEURON_UNIT, rtl/izhikevich_layer.v; the ULX3S
#           builds' engine), where the barrel shifter alone would not fit.
#  s16m:    the scale table's 16x16 skin at 1 MS/s as the ECP5 rows build
#           it (host/fpga/scale_table.h scale_scene; 40 MHz, the AD7476A's
#           first band at 1 MS/s): 32 DFT channels in 6 lanes at KS + 8 =
#           40 clocks a sample, the barrel shifter and the neuron unit's
#           5 lanes (NEURON_LANES, rtl/izhikevich_lanes.v).
#  s18m:    the same for 18x18: 36 channels in 6 lanes, a frame's sample
#           44 clocks;
#  s20m:    the same for 20x20: 40 channels in 7 lanes, 48 clocks;
#  s64:     scenes/skin64x64.yaml on the streaming datapath (below);
#  s32m:    32x32 on the frame engine, with the ADC on its own
#           40 MHz clock (ADC_CLK_HZ, rtl/stream_cdc.v) and the core at
#           50 MHz: 64 channels in 10 lanes, N 256, 2 Mbaud.
# ${out} = the list ${base} with each NAME=VALUE given replacing its
# -GNAME=... entry; a NAME the list lacks stops the configure (a build would
# otherwise keep the old value without a word).
function(dtmf_params_with out base)
  set(params ${${base}})
  foreach(nv ${ARGN})
    string(REGEX MATCH "^[A-Z_0-9]+" name "${nv}")
    set(found ${params})
    list(FILTER found INCLUDE REGEX "^-G${name}=")
    if(NOT found)
      message(FATAL_ERROR "dtmf_params_with: ${base} has no -G${name}")
    endif()
    list(TRANSFORM params REPLACE "^-G${name}=.*" "-G${nv}")
  endforeach()
  set(${out} ${params} PARENT_SCOPE)
endfunction()

set(dtmf_dir ${CMAKE_BINARY_DIR}/dtmf_top)
set(dtmf_default ${ESKIN_DTMF_TOP_PARAMS})  # top-level CMakeLists.txt
set(dtmf_s10 -GCLK_HZ=96000000 -GSAMPLE_HZ=70000 -GBAUD=3000000 -GKS=20 -GN=64 -GACC_W=19
  -GSTEP=70 -GIW=11 -GIMEM_WORDS=1280 -GDW=12 -GKW=8 -GOUT_DEPTH=2048 -GENGINE_FAST_SHIFT=0
  -GSDFT_LANES=3 -GNEURON_UNIT=0 -GADC_CLK_HZ=0)
# Every build with its simulation assertions (--assert): the microcode's
# timing contracts with the top's ports and the engine's return stack
# (rtl/dtmf_top.v, frame_engine.v, izhikevich_layer.v, izhikevich_lanes.v)
# stop any test of a top whose microcode breaks one.
set(eskin_default_args --assert ${dtmf_default} -GUCODE_HEX=\"${dtmf_dir}/neuroskin2.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/neuroskin2.krom.hex\")
eskin_verilate(${exe} Vdtmf_top_s10 ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_s10} --assert
  -GUCODE_HEX=\"${dtmf_dir}/staggered10x10.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/staggered10x10.krom.hex\")
dtmf_params_with(dtmf_s10fast dtmf_s10 CLK_HZ=48000000 ENGINE_FAST_SHIFT=1)
eskin_verilate(${exe} Vdtmf_top_s10fast ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_s10fast} --assert
  -GUCODE_HEX=\"${dtmf_dir}/staggered10x10_fast.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/staggered10x10_fast.krom.hex\")
dtmf_params_with(dtmf_s10unit dtmf_s10fast CLK_HZ=24000000 NEURON_UNIT=1)
eskin_verilate(${exe} Vdtmf_top_s10unit ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_s10unit} --assert
  -GUCODE_HEX=\"${dtmf_dir}/staggered10x10_unit.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/staggered10x10_unit.krom.hex\")
set(dtmf_s16m -GCLK_HZ=40000000 -GSAMPLE_HZ=1000000 -GBAUD=2000000 -GKS=32 -GN=128 -GACC_W=20
  -GSTEP=1000 -GIW=11 -GIMEM_WORDS=1280 -GDW=12 -GKW=9 -GOUT_DEPTH=2048 -GENGINE_FAST_SHIFT=1
  -GSDFT_LANES=6 -GNEURON_UNIT=1 -GNEURON_LANES=5 -GNEURON_BITS=9 -GCOLS=16 -GADC_CLK_HZ=0)
eskin_verilate(${exe} Vdtmf_top_s16m ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_s16m} --assert
  -GUCODE_HEX=\"${dtmf_dir}/scale_16x16_1msps.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/scale_16x16_1msps.krom.hex\")
dtmf_params_with(dtmf_s18m dtmf_s16m KS=36 NEURON_BITS=10 COLS=18)
eskin_verilate(${exe} Vdtmf_top_s18m ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_s18m} --assert
  -GUCODE_HEX=\"${dtmf_dir}/scale_18x18_1msps.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/scale_18x18_1msps.krom.hex\")
dtmf_params_with(dtmf_s20m dtmf_s16m KS=40 SDFT_LANES=7 COLS=20 NEURON_BITS=10)
eskin_verilate(${exe} Vdtmf_top_s20m ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_s20m} --assert
  -GUCODE_HEX=\"${dtmf_dir}/scale_20x20_1msps.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/scale_20x20_1msps.krom.hex\")
dtmf_params_with(dtmf_s32m dtmf_s20m
  KS=64 N=256 ACC_W=21 CLK_HZ=50000000 ADC_CLK_HZ=40000000 OUT_DEPTH=8192 SDFT_LANES=10
  NEURON_BITS=11 COLS=32)
eskin_verilate(${exe} Vdtmf_top_s32m ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_s32m} --assert
  -GUCODE_HEX=\"${dtmf_dir}/scale_32x32_1msps.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/scale_32x32_1msps.krom.hex\")
# p3s: scenes/planned3x3.yaml (bin-centred carriers: no demixing) on the
# streaming datapath (STREAM: rtl/dtmf_chain.v behind the DFT, the engine
# its control plane) at the UP5K's 18 MHz.
set(dtmf_p3s -GCLK_HZ=18000000 -GSAMPLE_HZ=35000 -GBAUD=3000000 -GKS=6 -GN=32 -GACC_W=18
  -GSTEP=35 -GIW=11 -GIMEM_WORDS=1280 -GDW=8 -GKW=8 -GOUT_DEPTH=512 -GENGINE_FAST_SHIFT=0
  -GSDFT_LANES=1 -GNEURON_UNIT=0 -GADC_CLK_HZ=0 -GSTREAM=1 -GROWS=3 -GCOLS=3 -GMAG_SHIFT=0
  -GMAX_SPIKES=256)
eskin_verilate(${exe} Vdtmf_top_p3s ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_p3s} --assert
  -GUCODE_HEX=\"${dtmf_dir}/planned3x3_stream.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/planned3x3_stream.krom.hex\")
# p3c: the same build for the commands test (its own microcode files: the
# test writes them with spikes on while p3s's test may run beside it).
eskin_verilate(${exe} Vdtmf_top_p3c ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_p3s} --assert
  -GUCODE_HEX=\"${dtmf_dir}/planned3x3_stream_cmd.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/planned3x3_stream_cmd.krom.hex\")
# s64: scenes/skin64x64.yaml (4096 taxels, 128 carriers at 1 MS/s) on the
# streaming datapath as the ULX3S flow builds it (40 MHz, 22 DFT lanes
# behind a 4-sample FIFO, the barrel shifter in the control plane).
set(dtmf_s64 -GCLK_HZ=40000000 -GSAMPLE_HZ=1000000 -GBAUD=2000000 -GKS=128 -GN=512 -GACC_W=22
  -GSTEP=1000 -GIW=11 -GIMEM_WORDS=1280 -GDW=11 -GKW=10 -GOUT_DEPTH=32768 -GENGINE_FAST_SHIFT=1
  -GSDFT_LANES=22 -GNEURON_UNIT=0 -GSDFT_FIFO=4 -GSTREAM=1 -GROWS=64 -GCOLS=64 -GMAG_SHIFT=4
  -GMAX_SPIKES=256 -GADC_CLK_HZ=0)
eskin_verilate(${exe} Vdtmf_top_s64 ${CMAKE_SOURCE_DIR}/rtl/dtmf_top.v dtmf_top ${dtmf_s64} --assert
  -GUCODE_HEX=\"${dtmf_dir}/skin64x64_stream.ucode.hex\"
  -GKROM_HEX=\"${dtmf_dir}/skin64x64_stream.krom.hex\")
string(JOIN " " dtmf_s64_str ${dtmf_s64})
string(JOIN " " dtmf_p3s_str ${dtmf_p3s})
string(JOIN " " dtmf_default_str ${dtmf_default})
string(JOIN " " dtmf_s10_str ${dtmf_s10})
string(JOIN " " dtmf_s10fast_str ${dtmf_s10fast})
string(JOIN " " dtmf_s10unit_str ${dtmf_s10unit})
string(JOIN " " dtmf_s16m_str ${dtmf_s16m})
string(JOIN " " dtmf_s18m_str ${dtmf_s18m})
string(JOIN " " dtmf_s20m_str ${dtmf_s20m})
string(JOIN " " dtmf_s32m_str ${dtmf_s32m})
target_compile_definitions(${exe} PRIVATE DTMF_TOP_DIR="${dtmf_dir}"
  DTMF_TOP_PARAMS="${dtmf_default_str}" DTMF_TOP_CLK_HZ=${ESKIN_DTMF_TOP_CLK_HZ}
  DTMF_TOP_S10_PARAMS="${dtmf_s10_str}" DTMF_TOP_S10_CLK_HZ=96000000
  DTMF_TOP_S10FAST_PARAMS="${dtmf_s10fast_str}" DTMF_TOP_S10FAST_CLK_HZ=48000000
  DTMF_TOP_S10UNIT_PARAMS="${dtmf_s10unit_str}" DTMF_TOP_S10UNIT_CLK_HZ=24000000
  DTMF_TOP_S16M_PARAMS="${dtmf_s16m_str}" DTMF_TOP_S16M_CLK_HZ=40000000
  DTMF_TOP_S18M_PARAMS="${dtmf_s18m_str}" DTMF_TOP_S18M_CLK_HZ=40000000
  DTMF_TOP_S20M_PARAMS="${dtmf_s20m_str}" DTMF_TOP_S20M_CLK_HZ=40000000
  DTMF_TOP_S32M_PARAMS="${dtmf_s32m_str}" DTMF_TOP_S32M_CLK_HZ=50000000
  DTMF_TOP_P3S_PARAMS="${dtmf_p3s_str}" DTMF_TOP_P3S_CLK_HZ=18000000
  DTMF_TOP_S64_PARAMS="${dtmf_s64_str}" DTMF_TOP_S64_CLK_HZ=40000000)
target_link_libraries(${exe} PRIVATE eskin_ucode eskin_fpga eskin_cycle)
# Verilator 5.006 leaves an unused delayed copy of power_on_reset's
# synchroniser in the code it writes for the two-clock build (s32m):
# GCC's -Wunused-but-set-variable on generated code, not ours.
target_compile_options(${exe} PRIVATE -Wno-unused-but-set-variable)
