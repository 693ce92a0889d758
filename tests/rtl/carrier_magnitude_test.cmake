# Builds of carrier_magnitude for tests/rtl/carrier_magnitude_test.cpp (each
# also linted with -Wall fatal):
#  default: ACC_W 24, MAG_W 16, SHIFT 8 (the DTMF chain's; never saturates);
#  w32:     ACC_W 32, MAG_W 30, SHIFT 1 (the widest: 64-bit P, 31 root
#           stages; the kernel's 2 SHIFT - 2 = 0 case; saturates);
#  s0:      ACC_W 20, MAG_W 16, SHIFT 0 (the kernel's SHIFT = 0 branch,
#           P << 2; saturates).
eskin_verilate(${exe} Vcarrier_magnitude_w32 ${CMAKE_SOURCE_DIR}/rtl/carrier_magnitude.v
  carrier_magnitude -GACC_W=32 -GMAG_W=30 -GSHIFT=1)
eskin_verilate(${exe} Vcarrier_magnitude_s0 ${CMAKE_SOURCE_DIR}/rtl/carrier_magnitude.v
  carrier_magnitude -GACC_W=20 -GMAG_W=16 -GSHIFT=0)
# ECP5 synthesis (Yosys synth_ecp5 through scripts/synth_ecp5.sh, figures in
# build/synth/carrier_magnitude_ecp5/stat.txt): the squares on MULT18X18D,
# two 24 x 24 signed products of 4 each; nothing else may take one.
add_test(NAME synth.carrier_magnitude_ecp5
  COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ecp5.sh carrier_magnitude
    --out ${CMAKE_BINARY_DIR}/synth/carrier_magnitude_ecp5)
set_tests_properties(synth.carrier_magnitude_ecp5 PROPERTIES LABELS synth TIMEOUT 900
  PASS_REGULAR_EXPRESSION "carrier_magnitude: yosys LUT4 [0-9]+, FF [0-9]+, MULT18X18D 8,")
# Placed and routed for the ECP5-85F at the streaming datapath's clock
# (50 MHz): must fit and meet it (Fmax in the output line).
add_test(NAME pnr.carrier_magnitude_ecp5
  COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ecp5.sh carrier_magnitude --pnr --freq 50 --device 85k
    --out ${CMAKE_BINARY_DIR}/synth/carrier_magnitude_ecp5_pnr)
set_tests_properties(pnr.carrier_magnitude_ecp5 PROPERTIES LABELS "synth;pnr" TIMEOUT 2400)
add_test(NAME lint.carrier_magnitude_rejects_illegal_parameters_shift
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module carrier_magnitude
    -GACC_W=24 -GMAG_W=16 -GSHIFT=25 ${CMAKE_SOURCE_DIR}/rtl/carrier_magnitude.v)
set_tests_properties(lint.carrier_magnitude_rejects_illegal_parameters_shift PROPERTIES LABELS lint
  PASS_REGULAR_EXPRESSION "carrier_magnitude_illegal_parameters")
