file(REMOVE_RECURSE
  "/work/main/build-tires/ws/devel/lib/lane_keeping/lk_simulate"
  "/work/main/build-tires/ws/devel/lib/lane_keeping/lk_simulate.pdb"
  "CMakeFiles/lk_simulate.dir/src/tools/lk_simulate.cpp.o"
  "CMakeFiles/lk_simulate.dir/src/tools/lk_simulate.cpp.o.d"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/lk_simulate.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
