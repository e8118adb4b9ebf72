# CMAKE generated file: DO NOT EDIT!
# Timestamp file for custom commands dependencies management for clean_test_results_lane_keeping.
