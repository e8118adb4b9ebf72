# Empty custom commands generated dependencies file for run_tests_lane_keeping.
# This may be replaced when dependencies are built.
