// The gap_monitor node: the GapMonitorRos role in its own process (the usual way beside a real car).
#include "gap_monitor_ros.h"
#include "node_shell.h"

int main(int argc, char** argv) { return lane_keeping::runNode<lane_keeping::GapMonitorRos>(argc, argv, "gap_monitor"); }
