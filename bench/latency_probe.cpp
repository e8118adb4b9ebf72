// lk_latency_probe: in a realtime run, how late each loop sample reaches a subscriber in another
// process, on the wall clock: arrival wall time - (wall time of the run's t = 0 + the sample's stamp).
// The plant publishes a sample as soon as it has computed the state for t (>= wall_start + t in
// realtime); the controllers publish theirs as soon as their delayed inputs are in, so their
// samples may arrive before their stamp (negative age: lookahead from the delays).
// Prints one line per topic when the run ends (RunStatus != RUNNING). Benchmarks only.
#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "lane_keeping/DesiredSteeringArray.h"
#include "lane_keeping/MeasuredSteeringArray.h"
#include "lane_keeping/RunStatus.h"
#include "lane_keeping/SteeringTorqueArray.h"
#include "lane_keeping/VehicleStateArray.h"
#include "topic_names.h"

namespace {

double wall_start = 0.0;
std::map<std::string, std::vector<double>> ages;  // [s] per topic

template <typename ArrayMsg>
void record(const std::string& topic, const typename ArrayMsg::ConstPtr& msg) {
  const double now = ros::WallTime::now().toSec();
  if (wall_start <= 0.0) return;
  for (const auto& sample : msg->samples) ages[topic].push_back(now - (wall_start + sample.header.stamp.toSec()));
}

void report() {
  std::printf("%-22s %10s %10s %10s %10s %10s %9s\n", "topic", "min_us", "p50_us", "p99_us", "p99.9_us", "max_us",
              "samples");
  for (auto& entry : ages) {
    std::vector<double>& v = entry.second;
    if (v.empty()) continue;
    std::sort(v.begin(), v.end());
    auto at = [&](double q) { return 1e6 * v[static_cast<std::size_t>(q * (v.size() - 1))]; };
    std::printf("%-22s %10.0f %10.0f %10.0f %10.0f %10.0f %9zu\n", entry.first.c_str(), 1e6 * v.front(), at(0.5),
                at(0.99), at(0.999), 1e6 * v.back(), v.size());
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lane_keeping;
  ros::init(argc, argv, "lk_latency_probe");
  ros::NodeHandle nh;
  const auto hints = ros::TransportHints().tcpNoDelay();
  auto status_sub = nh.subscribe<RunStatus>(topics::kRunStatus, 10, boost::function<void(const RunStatus::ConstPtr&)>([](const RunStatus::ConstPtr& s) {
    if (s->wall_start > 0.0) wall_start = s->wall_start;
    if (s->state != RunStatus::RUNNING) {
      report();
      ros::shutdown();
    }
  }));
  auto a = nh.subscribe<VehicleStateArray>(topics::kVehicleState, 10000,
      [](const VehicleStateArray::ConstPtr& m) { record<VehicleStateArray>(topics::kVehicleState, m); }, ros::VoidConstPtr(), hints);
  auto b = nh.subscribe<MeasuredSteeringArray>(topics::kMeasuredSteering, 10000,
      [](const MeasuredSteeringArray::ConstPtr& m) { record<MeasuredSteeringArray>(topics::kMeasuredSteering, m); }, ros::VoidConstPtr(), hints);
  auto c = nh.subscribe<DesiredSteeringArray>(topics::kDesiredSteering, 10000,
      [](const DesiredSteeringArray::ConstPtr& m) { record<DesiredSteeringArray>(topics::kDesiredSteering, m); }, ros::VoidConstPtr(), hints);
  auto d = nh.subscribe<SteeringTorqueArray>(topics::kSteeringTorque, 10000,
      [](const SteeringTorqueArray::ConstPtr& m) { record<SteeringTorqueArray>(topics::kSteeringTorque, m); }, ros::VoidConstPtr(), hints);
  ros::spin();
  return 0;
}
