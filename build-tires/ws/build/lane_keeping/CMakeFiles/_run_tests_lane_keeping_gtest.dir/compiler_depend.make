# Empty custom commands generated dependencies file for _run_tests_lane_keeping_gtest.
# This may be replaced when dependencies are built.
