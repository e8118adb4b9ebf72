# Empty custom commands generated dependencies file for clean_test_results_lane_keeping.
# This may be replaced when dependencies are built.
