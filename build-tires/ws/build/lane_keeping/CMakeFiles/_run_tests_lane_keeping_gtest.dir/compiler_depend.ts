# CMAKE generated file: DO NOT EDIT!
# Timestamp file for custom commands dependencies management for _run_tests_lane_keeping_gtest.
