# Second build: 3 sensors with ft_calibrate (the seed-002 top's command set).
eskin_verilate(${exe} Vhall_cmd_tb_ft ${CMAKE_CURRENT_SOURCE_DIR}/hall_cmd_tb.v hall_cmd_tb
  -GNS=3 -GHAS_FT=1)
