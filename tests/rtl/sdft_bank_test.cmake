# Second parameter set of sdft_bank: K_MAX 8 (5 carriers used), N 48 (not a
# power of two: N inc needs shift-and-add), 12-bit samples and
# coefficients, 8-bit table index, 2 term fraction bits and the narrowest
# legal accumulator (12 + 1 + 2 + 6 = 21 bits).
eskin_verilate(${exe} Vsdft_bank_odd ${CMAKE_SOURCE_DIR}/rtl/sdft_bank.v sdft_bank
  -GK_MAX=8 -GN=48 -GXW=12 -GCW=12 -GTW=8 -GACC_W=21 -GFB=2)
