# Extra parameter sets of i2c_master (the default build is 12 MHz, 400 kHz):
#  std:     100 kHz standard mode.
#  badlow:  negative control, TLOW_NS 800 (with THIGH_NS 1500): tLOW too short.
#  badhigh: negative control, THIGH_NS 300: tHIGH too short.
foreach(set "std;-GSCL_HZ=100000" "badlow;-GTLOW_NS=800;-GTHIGH_NS=1500"
            "badhigh;-GTHIGH_NS=300")
  list(GET set 0 tag)
  list(SUBLIST set 1 -1 params)
  eskin_verilate(${exe} Vi2c_master_${tag} ${CMAKE_SOURCE_DIR}/rtl/i2c_master.v i2c_master ${params})
endforeach()
