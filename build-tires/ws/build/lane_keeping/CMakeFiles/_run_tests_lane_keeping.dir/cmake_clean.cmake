
# Per-language clean rules from dependency scanning.
foreach(lang )
  include(CMakeFiles/_run_tests_lane_keeping.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
