# frame_engine: the self-test program assembled by the CLI at build time
# (IMEM of the DW=14 set by $readmemh, checked by SelfTestFromUcodeHex), the
# second parameter set (IW 10, DW 14: the SPRAM DMEM, KW 8), lint at both
# sets the test builds, and the core placed and routed for the UP5K.
set(fe_selftest_src ${CMAKE_CURRENT_SOURCE_DIR}/frame_engine_selftest.fe)
set(fe_selftest_hex ${CMAKE_CURRENT_BINARY_DIR}/frame_engine_selftest.hex)
add_custom_command(OUTPUT ${fe_selftest_hex}
  COMMAND eskin ucode asm ${fe_selftest_src} -o ${fe_selftest_hex} --iw 10 -D EV_GO=1 -D OUT=0x100
  DEPENDS eskin ${fe_selftest_src} VERBATIM)
add_custom_target(frame_engine_selftest_hex DEPENDS ${fe_selftest_hex})
add_dependencies(${exe} frame_engine_selftest_hex)
target_compile_definitions(${exe} PRIVATE FRAME_ENGINE_SELFTEST_HEX="${fe_selftest_hex}")
target_link_libraries(${exe} PRIVATE eskin_ucode)
# Every build with its simulation assertions (the return stack's; the
# random programs switch them off and compare the overflow count instead).
set(eskin_default_args --assert)
set(fe_dw14_params -GIW=10 -GDW=14 -GKW=8 -GKROM_INIT=8192'h0 "-GUCODE_HEX=\"${fe_selftest_hex}\"")
verilate(${exe} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/frame_engine_tb.v
  TOP_MODULE frame_engine_tb PREFIX Vframe_engine_tb_dw14
  VERILATOR_ARGS -y ${CMAKE_SOURCE_DIR}/rtl -Wno-fatal --x-assign unique --x-initial unique -O3
    --assert ${fe_dw14_params})

# Third set: the barrel shifter (FAST_SHIFT 1; IW 10 for the directed
# shift program, DW 8, KW 4 with the bench's KROM_INIT).
set(fe_fast_params -GIW=10 -GFAST_SHIFT=1)
verilate(${exe} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/frame_engine_tb.v
  TOP_MODULE frame_engine_tb PREFIX Vframe_engine_tb_fast
  VERILATOR_ARGS -y ${CMAKE_SOURCE_DIR}/rtl -Wall --x-assign unique --x-initial unique -O3
    --assert ${fe_fast_params})
add_test(NAME lint.frame_engine_tb_fast
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module frame_engine_tb
    ${fe_fast_params} ${CMAKE_CURRENT_SOURCE_DIR}/frame_engine_tb.v)
set_tests_properties(lint.frame_engine_tb_fast PROPERTIES LABELS lint)
add_test(NAME lint.frame_engine_rejects_fast_shift2
  COMMAND verilator --lint-only -Wall -GFAST_SHIFT=2 ${CMAKE_SOURCE_DIR}/rtl/frame_engine.v)
set_tests_properties(lint.frame_engine_rejects_fast_shift2 PROPERTIES LABELS lint
  PASS_REGULAR_EXPRESSION "frame_engine_parameter_FAST_SHIFT_must_be_0_or_1")

# Lint (every warning fatal) at every set built here: the bench's defaults
# (IW 9, DW 8, KW 4 with its KROM_INIT), the DW=14 set, and the place-and-
# route wrapper's (IW 10, DW 14, KW 8).
add_test(NAME lint.frame_engine_tb
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module frame_engine_tb
    ${CMAKE_CURRENT_SOURCE_DIR}/frame_engine_tb.v)
add_test(NAME lint.frame_engine_tb_dw14
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module frame_engine_tb
    ${fe_dw14_params} ${CMAKE_CURRENT_SOURCE_DIR}/frame_engine_tb.v)
add_test(NAME lint.frame_engine_pnr
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module frame_engine_pnr
    "-GUCODE_HEX=\"${fe_selftest_hex}\"" ${CMAKE_CURRENT_SOURCE_DIR}/frame_engine_pnr.v)
set_tests_properties(lint.frame_engine_tb lint.frame_engine_tb_dw14 lint.frame_engine_pnr
  PROPERTIES LABELS lint)

# The core (IW 10 with the self-test program, DW 14: SPRAM, KW 8) in the
# small pin wrapper tests/rtl/frame_engine_pnr.v, placed and routed for the
# UP5K: must fit and reach 13.2 MHz (12 MHz + 10 %). Figures:
# build/synth/frame_engine_pnr/ (docs/frame_engine.md, "Resources").
add_test(NAME pnr.frame_engine
  COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ice40.sh ${CMAKE_CURRENT_SOURCE_DIR}/frame_engine_pnr.v
    --param "UCODE_HEX=\"${fe_selftest_hex}\"" --pnr --freq 13.2
    --out ${CMAKE_BINARY_DIR}/synth/frame_engine_pnr)
set_tests_properties(pnr.frame_engine PROPERTIES LABELS "synth;pnr" TIMEOUT 1200)

# Illegal parameters stop elaboration in both tools (IW 13 > 12, DW 3 < 4),
# with the message naming the parameter and its range.
add_test(NAME lint.frame_engine_rejects_iw13
  COMMAND verilator --lint-only -Wall -GIW=13 ${CMAKE_SOURCE_DIR}/rtl/frame_engine.v)
add_test(NAME synth.frame_engine_rejects_dw3
  COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ice40.sh frame_engine --param DW=3
    --out ${CMAKE_BINARY_DIR}/synth/frame_engine_dw3)
set_tests_properties(lint.frame_engine_rejects_iw13 PROPERTIES LABELS lint
  PASS_REGULAR_EXPRESSION "frame_engine_parameter_IW_must_be_4_to_12")
set_tests_properties(synth.frame_engine_rejects_dw3 PROPERTIES LABELS synth
  PASS_REGULAR_EXPRESSION "frame_engine_parameter_DW_must_be_4_to_15")
