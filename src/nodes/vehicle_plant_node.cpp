// The vehicle_plant node: the VehiclePlantRos role in its own process.
#include "node_shell.h"
#include "vehicle_plant_ros.h"

int main(int argc, char** argv) { return lane_keeping::runNode<lane_keeping::VehiclePlantRos>(argc, argv, "vehicle_plant"); }
