
# Per-language clean rules from dependency scanning.
foreach(lang )
  include(CMakeFiles/run_tests_lane_keeping_gtest.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
