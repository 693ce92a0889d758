# cmake -DIN=file -DOUT=header -DNAME=symbol -P embed_text.cmake: writes a
# header defining `static const char NAME[]` with the file's text, as a
# list of raw-string pieces (each below compilers' string-literal limits).
file(READ ${IN} text)
string(LENGTH "${text}" n)
set(out "// Generated from ${IN} by ucode/embed_text.cmake; do not edit.\n#pragma once\nstatic const char ${NAME}[] =\n")
set(pos 0)
while(pos LESS n)
  string(SUBSTRING "${text}" ${pos} 8000 piece)
  string(APPEND out "R\"eskin_embed(${piece})eskin_embed\"\n")
  math(EXPR pos "${pos} + 8000")
endwhile()
string(APPEND out ";\n")
file(WRITE ${OUT} "${out}")
