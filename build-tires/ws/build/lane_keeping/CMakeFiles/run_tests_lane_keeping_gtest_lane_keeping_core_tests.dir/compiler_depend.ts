# CMAKE generated file: DO NOT EDIT!
# Timestamp file for custom commands dependencies management for run_tests_lane_keeping_gtest_lane_keeping_core_tests.
