file(REMOVE_RECURSE
  "CMakeFiles/clean_test_results_lane_keeping"
)

# Per-language clean rules from dependency scanning.
foreach(lang )
  include(CMakeFiles/clean_test_results_lane_keeping.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
