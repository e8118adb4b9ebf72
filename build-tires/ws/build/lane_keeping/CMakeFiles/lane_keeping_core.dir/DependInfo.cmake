
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/build-tires/ws/src/lane_keeping/src/core/brush_tire.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/brush_tire.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/brush_tire.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/closed_loop.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/closed_loop.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/closed_loop.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/divergence_monitor.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/divergence_monitor.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/divergence_monitor.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/errors.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/errors.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/errors.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/flat_params.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/flat_params.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/flat_params.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/log_row.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/log_row.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/log_row.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/lugre_distributed_tire.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/lugre_distributed_tire.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/lugre_distributed_tire.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/lugre_lumped_tire.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/lugre_lumped_tire.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/lugre_lumped_tire.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/oscillation.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/oscillation.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/oscillation.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/param_readers.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/param_readers.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/param_readers.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/path.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/path.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/path.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/path_tracker.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/path_tracker.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/path_tracker.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/run_summary.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/run_summary.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/run_summary.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/signals.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/signals.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/signals.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/sim_config.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/sim_config.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/sim_config.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/single_track_model.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/single_track_model.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/single_track_model.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/steering_actuator.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/steering_actuator.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/steering_actuator.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/time.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/time.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/time.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/tire.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/tire.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/tire.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/tire_params.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/tire_params.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/tire_params.cpp.o.d"
  "/work/main/build-tires/ws/src/lane_keeping/src/core/vehicle_plant.cpp" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/vehicle_plant.cpp.o" "gcc" "lane_keeping/CMakeFiles/lane_keeping_core.dir/src/core/vehicle_plant.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
