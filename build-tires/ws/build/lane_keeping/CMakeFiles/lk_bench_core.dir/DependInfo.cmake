
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/build-tires/ws/src/lane_keeping/bench/bench_core.cpp" "lane_keeping/CMakeFiles/lk_bench_core.dir/bench/bench_core.cpp.o" "gcc" "lane_keeping/CMakeFiles/lk_bench_core.dir/bench/bench_core.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build-tires/ws/build/lane_keeping/CMakeFiles/lane_keeping_core.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
