file(REMOVE_RECURSE
  "/work/main/build-tires/ws/devel/lib/lane_keeping/lk_bench_core"
  "/work/main/build-tires/ws/devel/lib/lane_keeping/lk_bench_core.pdb"
  "CMakeFiles/lk_bench_core.dir/bench/bench_core.cpp.o"
  "CMakeFiles/lk_bench_core.dir/bench/bench_core.cpp.o.d"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/lk_bench_core.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
