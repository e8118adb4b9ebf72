# Empty dependencies file for lane_keeping_core.
# This may be replaced when dependencies are built.
