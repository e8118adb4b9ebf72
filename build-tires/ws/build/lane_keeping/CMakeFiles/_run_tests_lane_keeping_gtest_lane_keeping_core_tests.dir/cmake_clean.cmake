file(REMOVE_RECURSE
  "CMakeFiles/_run_tests_lane_keeping_gtest_lane_keeping_core_tests"
)

# Per-language clean rules from dependency scanning.
foreach(lang )
  include(CMakeFiles/_run_tests_lane_keeping_gtest_lane_keeping_core_tests.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
