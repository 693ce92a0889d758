# Extra parameter sets of i2c_master (the default build is 12 MHz, 400 kHz):
#  std:     100 kHz standard mode.
#  badlow:  negative control, TLOW_NS 800 (with THIGH_NS 1500): tLOW too short.
#  badhigh: negative control, THIGH_NS 300: tHIGH too short.
foreach(set "std;-GSCL_HZ=100000" "badlow;-GTLOW_NS=800;-GTHIGH_NS=1500"
            "badhigh;-GTHIGH_NS=300")
  list(GET set 0 tag)
  list(SUBLIST set 1 -1 params)
  verilate(${exe} SOURCES ${CMAKE_SOURCE_DIR}/rtl/i2c_master.v
    TOP_MODULE i2c_master PREFIX Vi2c_master_${tag}
    VERILATOR_ARGS -Wno-fatal --x-assign unique --x-initial unique -O3 ${params})
  add_test(NAME lint.i2c_master.${tag}
    COMMAND verilator --lint-only -Wall --top-module i2c_master ${params}
      ${CMAKE_SOURCE_DIR}/rtl/i2c_master.v)
  set_tests_properties(lint.i2c_master.${tag} PROPERTIES LABELS lint)
endforeach()
