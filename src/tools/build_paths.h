#pragma once
// Where this build's files are: the package's source folder (the tools' plotting scripts, the tests'
// configurations and fixtures) and the folder of its binaries (the tests run lk_simulate and the other tools as a
// user does). Defined in one source file CMake generates in the build folder (CMakeLists.txt,
// lane_keeping_build_paths), not as -D defines: an absolute path on the compiler's command line made every object
// of a test binary differ between two clones of the repository, so a fresh clone rebuilt them all instead of
// taking them from ccache (issue 45). Now only that generated file differs.

namespace lane_keeping::build_paths {

/// The package's source folder this build was configured from (in the catkin workspace: build/ws/src/lane_keeping).
const char* sourceDir();
/// The folder of the package's binaries in the devel space (lk_simulate, lk_gap, lk_stability, lk_gap_benchmark).
const char* toolsDir();
/// lk_simulate in that folder.
const char* lkSimulateBinary();

}  // namespace lane_keeping::build_paths
