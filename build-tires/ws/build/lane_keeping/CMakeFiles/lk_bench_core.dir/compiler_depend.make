# Empty compiler generated dependencies file for lk_bench_core.
# This may be replaced when dependencies are built.
