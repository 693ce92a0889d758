# hall_top builds of the figure (docs/hall_fpga.md), besides the default one:
#  16s: scenes/hall_000_skin.yaml as sim/hall_top_spec.h generates it (the
#       test checks): 16 sensors on 4 buses of 4 (0x0C..0x0F per bus, no mux).
#  mux8: 16 sensors on 2 buses of 8, all 0x0C behind TCA9548A channels 0..7:
#        too many per bus to keep up with 2053 us conversions.
#  deltas: the 16s build with the decoding the seed-000 scene asks for
#          (hall_baseline and the command path: DELTAS=1).
#  002: scenes/hall_002_magtac.yaml as generated (the test checks): 1 bus of
#       3 sensors, hall_baseline, ft_calibrate and the command path.
#  001: scenes/hall_001_split.yaml as generated: 1 sensor, hall_baseline,
#       hall_decouple and the command path.
#  003: scenes/hall_003_metamaterial.yaml as generated: 9 sensors behind a
#       TCA9548A on 1 bus, hall_baseline, force_curve (9 cells) and the
#       command path.
set(hall_16s -GNB=4 -GNSB=4 -GADDR=112'h1e3868c1e3868c1e3868c1e3868c
  -GMUX_ADDR=112'h0000000000000000000000000000 -GMUX_CH=48'h000000000000 -GREG0=16'h007c
  -GREG1=16'he380 -GREG2=16'h0008 -GCONV_CYC=29564 -GSTALE_CYC=36954)
set(hall_mux8 -GNB=2 -GNSB=8 "-GADDR=112'h183060c183060c183060c183060c"
  "-GMUX_ADDR=112'he1c3870e1c3870e1c3870e1c3870" "-GMUX_CH=48'hfac688fac688")
set(hall_deltas ${hall_16s} -GDELTAS=1)
set(hall_002 -GNB=1 -GNSB=3 -GADDR=21'h03868c -GMUX_ADDR=21'h000000 -GMUX_CH=9'h000
  -GREG0=16'h000c -GREG1=16'he380 -GREG2=16'h0008 -GCONV_CYC=29564 -GSTALE_CYC=36954 -GDELTAS=1
  -GFT=1 -GFT_ID=0)
set(hall_001 -GNB=1 -GNSB=1 -GADDR=7'h0c -GMUX_ADDR=7'h00 -GMUX_CH=3'h0 -GREG0=16'h007c
  -GREG1=16'he380 -GREG2=16'h0008 -GCONV_CYC=29564 -GSTALE_CYC=36954 -GDELTAS=1 -GDECOUPLE=1
  -GDEC_ID=0 -GDEC_GAIN_X=32'd9830 -GDEC_GAIN_Y=32'd9830 -GDEC_GAIN_Z=32'd15860)
set(hall_003 -GNB=1 -GNSB=9 -GADDR=63'h0e1a3070d183868c -GMUX_ADDR=63'h70e1c3870e1c3870
  -GMUX_CH=27'h2489200 -GREG0=16'h003c -GREG1=16'he380 -GREG2=16'h0008 -GCONV_CYC=29564
  -GSTALE_CYC=36954 -GDELTAS=1 -GCURVE=1 -GCURVE_ID=0 -GNC=9 -GCURVE_NB=13 -GCURVE_NR=3
  -GCURVE_GAIN_X=16'd1540 -GCURVE_GAIN_Y=16'd1540 -GCURVE_GAIN_Z=16'd2478
  -GLOCK_MN=96'h00003f48000012c000000384)
foreach(tag 16s mux8 deltas 002 001 003)
  eskin_verilate(${exe} Vhall_top_${tag} ${CMAKE_SOURCE_DIR}/rtl/hall_top.v hall_top ${hall_${tag}})
endforeach()
# The decoding's modules are read by Yosys as submodules (plain Verilog, no
# casts): synthesise the seed-002 build, which has them all. Its place and
# route on the UP5K at 12 MHz (it fits since hall_baseline keeps its state
# in block RAM) is bitstream.icebreaker_hall_002's, the same core in the
# iCEBreaker's wrapper (tests/fpga/CMakeLists.txt).
set(hall_002_synth "")
foreach(p ${hall_002})
  string(REGEX REPLACE "^-G" "" p ${p})
  list(APPEND hall_002_synth --param ${p})
endforeach()
add_test(NAME synth.hall_top_002
  COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ice40.sh hall_top ${hall_002_synth}
    --out ${CMAKE_BINARY_DIR}/synth/hall_top_002)
set_tests_properties(synth.hall_top_002 PROPERTIES LABELS synth TIMEOUT 600)
# Every Hall module stops an illegal parameter set at elaboration, naming
# the rule it broke (one set per module; module|parameters|the stop's name).
set(hall_illegal_sets
  "hall_top|-GFT=1|hall_top_FT_needs_DELTAS"                       # F/T without the baseline
  "hall_cmd|-GHAS_FT=1 -GHAS_BASELINE=0|hall_cmd_HAS_FT_needs_HAS_BASELINE"
  "hall_top|-GDECOUPLE=1|hall_top_DECOUPLE_needs_DELTAS|_decouple"  # decoupling without the baseline
  "hall_top|-GDELTAS=1 -GCURVE=1 -GNC=5|hall_top_CURVE_needs_DELTAS_and_sensors|_curve"  # 5 cells, 4 sensors
  "hall_cmd|-GHAS_CURVE=1 -GHAS_BASELINE=0|hall_cmd_HAS_CURVE_and_HAS_DECOUPLE_need_HAS_BASELINE|_curve"
  "hall_baseline|-GNS=65|illegal_parameter_NS_must_be_1_to_64"
  "ft_calibrate|-GC_FRAC=31|illegal_parameter_C_FRAC_must_be_1_to_30"
  "force_curve|-GNB=2|illegal_parameter_NB_must_be_3_to_32"
  "hall_decouple|-GID=256|illegal_parameter_ID_must_be_0_to_255"
  "i2c_master|-GSCL_HZ=1000000|i2c_master_SCL_HZ_above_400kHz_is_not_supported"
  "mlx90393_sequencer|-GNS=65|mlx90393_sequencer_NS_must_be_1_to_64")
foreach(set ${hall_illegal_sets})
  string(REPLACE "|" ";" parts "${set}")
  list(GET parts 0 mod)
  list(GET parts 1 params)
  list(GET parts 2 stop)
  set(suffix "")  # a second set of one module names itself
  list(LENGTH parts n)
  if(n GREATER 3)
    list(GET parts 3 suffix)
  endif()
  separate_arguments(params)
  add_test(NAME lint.${mod}_rejects_illegal_parameters${suffix}
    COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module ${mod} ${params}
      ${CMAKE_SOURCE_DIR}/rtl/${mod}.v)
  set_tests_properties(lint.${mod}_rejects_illegal_parameters${suffix} PROPERTIES LABELS lint
    PASS_REGULAR_EXPRESSION "${stop}")
endforeach()
