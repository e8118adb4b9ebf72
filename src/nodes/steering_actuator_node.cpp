// The steering_actuator node: the SteeringActuatorRos role in its own process.
#include "node_shell.h"
#include "steering_actuator_ros.h"

int main(int argc, char** argv) { return lane_keeping::runNode<lane_keeping::SteeringActuatorRos>(argc, argv, "steering_actuator"); }
