# 16-bit tokens, so that every token of a run is distinct (the top crosses 60).
set(eskin_default_args -GW=16)
