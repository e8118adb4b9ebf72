# Empty compiler generated dependencies file for lk_simulate.
# This may be replaced when dependencies are built.
