# CMAKE generated file: DO NOT EDIT!
# Timestamp file for custom commands dependencies management for run_tests_lane_keeping.
