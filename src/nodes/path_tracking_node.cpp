// The path_tracking node: the PathTrackingRos role in its own process.
#include "node_shell.h"
#include "path_tracking_ros.h"

int main(int argc, char** argv) { return lane_keeping::runNode<lane_keeping::PathTrackingRos>(argc, argv, "path_tracking"); }
