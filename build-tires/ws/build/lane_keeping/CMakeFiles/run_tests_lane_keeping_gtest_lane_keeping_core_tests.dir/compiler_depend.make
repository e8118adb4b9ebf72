# Empty custom commands generated dependencies file for run_tests_lane_keeping_gtest_lane_keeping_core_tests.
# This may be replaced when dependencies are built.
