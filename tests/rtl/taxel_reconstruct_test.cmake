# Builds of taxel_reconstruct for tests/rtl/taxel_reconstruct_test.cpp (each
# also linted with -Wall fatal): the default (R_MAX = C_MAX = 3, the 3x3
# skin, 6 carriers) and x64 (64 x 64 taxels, 128 carriers).
eskin_verilate(${exe} Vtaxel_reconstruct_x64 ${CMAKE_SOURCE_DIR}/rtl/taxel_reconstruct.v
  taxel_reconstruct -GR_MAX=64 -GC_MAX=64)
# ECP5 synthesis (Yosys synth_ecp5, figures in build/synth/NAME/stat.txt) at
# both sizes: one 15 x 30 multiplier (2 MULT18X18D) for every taxel and line
# product, nothing else on a DSP.
foreach(tr_set "taxel_reconstruct_ecp5|-"
               "taxel_reconstruct_x64_ecp5|--param;R_MAX=64;--param;C_MAX=64")
  string(REPLACE "|" ";" tr_parts "${tr_set}")
  list(GET tr_parts 0 tr_name)
  list(SUBLIST tr_parts 1 -1 tr_params)
  list(REMOVE_ITEM tr_params "-")
  add_test(NAME synth.${tr_name}
    COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ecp5.sh taxel_reconstruct ${tr_params}
      --out ${CMAKE_BINARY_DIR}/synth/${tr_name})
  set_tests_properties(synth.${tr_name} PROPERTIES LABELS synth TIMEOUT 900
    PASS_REGULAR_EXPRESSION "taxel_reconstruct: yosys LUT4 [0-9]+, FF [0-9]+, MULT18X18D 2,")
endforeach()
# The 64 x 64 block placed and routed for the ECP5-85F at 50 MHz: must fit
# and meet it (Fmax in the output line).
add_test(NAME pnr.taxel_reconstruct_x64_ecp5
  COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ecp5.sh taxel_reconstruct --param R_MAX=64
    --param C_MAX=64 --pnr --freq 50 --device 85k
    --out ${CMAKE_BINARY_DIR}/synth/taxel_reconstruct_x64_ecp5_pnr)
set_tests_properties(pnr.taxel_reconstruct_x64_ecp5 PROPERTIES LABELS "synth;pnr" TIMEOUT 2400)
# Sizes whose line index does not fit 8 bits.
add_test(NAME lint.taxel_reconstruct_rejects_illegal_parameters_k
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module taxel_reconstruct
    -GR_MAX=200 -GC_MAX=56 ${CMAKE_SOURCE_DIR}/rtl/taxel_reconstruct.v)
set_tests_properties(lint.taxel_reconstruct_rejects_illegal_parameters_k PROPERTIES LABELS lint
  PASS_REGULAR_EXPRESSION "taxel_reconstruct_illegal_parameters")
