# Three sources (mixed_top uses two): round robin with a source in the middle.
set(eskin_default_args -GNS=3)
