# Builds of izhikevich_pipe for tests/rtl/izhikevich_pipe_test.cpp (each
# also linted with -Wall fatal): N 9 (the 3x3 skin: fewer neurons than
# stages) and N 4096 (64x64).
set(eskin_default_args -GN=9)
eskin_verilate(${exe} Vizhikevich_pipe_4096 ${CMAKE_SOURCE_DIR}/rtl/izhikevich_pipe.v
  izhikevich_pipe -GN=4096)
add_test(NAME lint.izhikevich_pipe_rejects_illegal_parameters
  COMMAND verilator --lint-only -Wall -y ${CMAKE_SOURCE_DIR}/rtl --top-module izhikevich_pipe
    -GN=0 ${CMAKE_SOURCE_DIR}/rtl/izhikevich_pipe.v)
set_tests_properties(lint.izhikevich_pipe_rejects_illegal_parameters PROPERTIES LABELS lint
  PASS_REGULAR_EXPRESSION "izhikevich_pipe_illegal_parameters")
# At 64x64 through Yosys synth_ecp5: figures in
# build/synth/izhikevich_pipe_ecp5_4096/. Eight 16 x 16 products, one
# MULT18X18D each.
add_test(NAME synth.ecp5_izhikevich_pipe_4096
  COMMAND ${CMAKE_SOURCE_DIR}/scripts/synth_ecp5.sh izhikevich_pipe --param N=4096
    --out ${CMAKE_BINARY_DIR}/synth/izhikevich_pipe_ecp5_4096)
set_tests_properties(synth.ecp5_izhikevich_pipe_4096 PROPERTIES LABELS synth TIMEOUT 900
  PASS_REGULAR_EXPRESSION "izhikevich_pipe: yosys LUT4 [0-9]+, FF [0-9]+, MULT18X18D 8,")
