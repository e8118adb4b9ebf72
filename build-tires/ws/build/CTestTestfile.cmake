# CMake generated Testfile for 
# Source directory: /work/main/build-tires/ws/src
# Build directory: /work/main/build-tires/ws/build
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
subdirs("lane_keeping")
