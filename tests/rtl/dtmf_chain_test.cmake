# Builds of dtmf_chain for tests/rtl/dtmf_chain_test.cpp (each also linted
# with -Wall fatal): the default 3x3 skin (N 32: MAG_SHIFT 0), the 10x10
# scene's (N 64: MAG_SHIFT 1) and 64x64 (128 carriers, N 512: MAG_SHIFT 4,
# 1024 spike events a window), the ECP5-85F's streaming target.
set(eskin_default_args -GR=3 -GC=3 -GMAG_SHIFT=0)
eskin_verilate(${exe} Vdtmf_chain_10 ${CMAKE_SOURCE_DIR}/rtl/dtmf_chain.v dtmf_chain
  -GR=10 -GC=10 -GMAG_SHIFT=1)
eskin_verilate(${exe} Vdtmf_chain_64 ${CMAKE_SOURCE_DIR}/rtl/dtmf_chain.v dtmf_chain
  -GR=64 -GC=64 -GMAG_SHIFT=4 -GMAX_SPIKES=1024)
# Illegal sets stop at elaboration: no skin, and 256 carriers (k is 8 bits).
foreach(set "|-GR=0" "_k|-GR=200;-GC=56")
  string(REPLACE "|" ";" parts "${set}")
  list(GET parts 0 suffix)
  list(SUBLIST parts 1 -1 params)
  add_test(NAME lint.dtmf_chain_rejects_illegal_parameters${suffix}
    COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module dtmf_chain
      ${params} ${CMAKE_SOURCE_DIR}/rtl/dtmf_chain.v)
  set_tests_properties(lint.dtmf_chain_rejects_illegal_parameters${suffix} PROPERTIES LABELS lint
    PASS_REGULAR_EXPRESSION "dtmf_chain_illegal_parameters")
endforeach()
# The 64x64 datapath through Yosys synth_ecp5 (scripts/synth_ecp5.sh, the
# ECP5 tools from build/venv): figures in build/synth/dtmf_chain_ecp5_64x64/.
# 26 MULT18X18D: carrier_magnitude's 8, taxel_reconstruct's 2, each layer's
# 8; nothing else may take one.
add_test(NAME synth.ecp5_dtmf_chain_64x64
  COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ecp5.sh dtmf_chain --param R=64 --param C=64
    --param MAG_SHIFT=4 --param MAX_SPIKES=1024 --out ${CMAKE_BINARY_DIR}/synth/dtmf_chain_ecp5_64x64)
set_tests_properties(synth.ecp5_dtmf_chain_64x64 PROPERTIES LABELS synth TIMEOUT 900
  PASS_REGULAR_EXPRESSION "dtmf_chain: yosys LUT4 [0-9]+, FF [0-9]+, MULT18X18D 26,")
# The pin wrapper for placing the 64x64 datapath on the ECP5-85F
# (tests/rtl/dtmf_chain_pnr.v: its ports outnumber the package's pins).
add_test(NAME lint.dtmf_chain_pnr
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module dtmf_chain_pnr
    ${CMAKE_CURRENT_SOURCE_DIR}/dtmf_chain_pnr.v)
set_tests_properties(lint.dtmf_chain_pnr PROPERTIES LABELS lint)
# Its placement (scripts/synth_ecp5.sh tests/rtl/dtmf_chain_pnr.v --pnr
# --freq 50 --device 85k --out DIR) takes several minutes of this machine's
# two cores, too long for the default run: the 64x64 build's place and route
# belongs to the scale table's real runs (eskin bitstream --scale-table).
