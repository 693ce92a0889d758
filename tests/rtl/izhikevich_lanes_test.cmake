# The Verilated lanes for tests/rtl/izhikevich_lanes_test.cpp: 5 lanes (the
# ULX3S's), a 4 x 7 skin's two layers (56 neurons, 6 index bits).
set(eskin_default_args -GLANES=5 -GNB=6 -GCOLS=7 --assert)
