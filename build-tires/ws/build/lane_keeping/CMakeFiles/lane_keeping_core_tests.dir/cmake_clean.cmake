file(REMOVE_RECURSE
  "/work/main/build-tires/ws/devel/lib/lane_keeping/lane_keeping_core_tests"
  "/work/main/build-tires/ws/devel/lib/lane_keeping/lane_keeping_core_tests.pdb"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/brush_tire_test.cpp.o"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/brush_tire_test.cpp.o.d"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/contact_pressure_test.cpp.o"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/contact_pressure_test.cpp.o.d"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/lugre_distributed_tire_test.cpp.o"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/lugre_distributed_tire_test.cpp.o.d"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/lugre_lumped_tire_test.cpp.o"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/lugre_lumped_tire_test.cpp.o.d"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/magic_formula_tire_test.cpp.o"
  "CMakeFiles/lane_keeping_core_tests.dir/test/core/magic_formula_tire_test.cpp.o.d"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/lane_keeping_core_tests.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
