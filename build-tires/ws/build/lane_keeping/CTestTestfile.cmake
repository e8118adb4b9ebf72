# CMake generated Testfile for 
# Source directory: /work/main/build-tires/ws/src/lane_keeping
# Build directory: /work/main/build-tires/ws/build/lane_keeping
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
add_test(_ctest_lane_keeping_gtest_lane_keeping_core_tests "/work/main/build-tires/ws/build/catkin_generated/env_cached.sh" "/usr/bin/python3" "/usr/share/catkin/cmake/test/run_tests.py" "/work/main/build-tires/ws/build/test_results/lane_keeping/gtest-lane_keeping_core_tests.xml" "--working-dir" "/work/main/build-tires/ws/src/lane_keeping" "--return-code" "/work/main/build-tires/ws/devel/lib/lane_keeping/lane_keeping_core_tests --gtest_output=xml:/work/main/build-tires/ws/build/test_results/lane_keeping/gtest-lane_keeping_core_tests.xml")
set_tests_properties(_ctest_lane_keeping_gtest_lane_keeping_core_tests PROPERTIES  _BACKTRACE_TRIPLES "/usr/share/catkin/cmake/test/tests.cmake;160;add_test;/usr/share/catkin/cmake/test/gtest.cmake;98;catkin_run_tests_target;/usr/share/catkin/cmake/test/gtest.cmake;37;_catkin_add_google_test;/work/main/build-tires/ws/src/lane_keeping/CMakeLists.txt;49;catkin_add_gtest;/work/main/build-tires/ws/src/lane_keeping/CMakeLists.txt;0;")
