# Empty dependencies file for lane_keeping_core_tests.
# This may be replaced when dependencies are built.
