#include "lane_keeping/gap/replay/tracker_replay.h"

#include <algorithm>
#include <cmath>

#include "lane_keeping/control/path_tracker.h"
#include "lane_keeping/gap/replay/replay_shooting.h"

namespace lane_keeping {

using C = LogSignals::Channel;
using namespace replay;

SubsystemReplay replayTracker(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments) {
  SubsystemReplay out;
  out.name = "tracker";
  const PathTracker tracker(config.tracker, createPath(config.path));
  const double tau = config.delays.pose_to_tracker;
  ReplayTrace trace = makeTrace("delta_des", log.samples(C::kDeltaDes));
  const auto& times = log.times();
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    if (!inSegments(t, segments) || t - tau < log.start()) continue;
    const double q = t - tau;  // Beregi eq 11: the pose tau1 earlier
    // Nearest samples carried along the smoothed pose (LogSignals::nearestAlongSmoothed): interpolating
    // the noisy samples made the noise depend on where between samples t - tau falls, and a fitted
    // delay chased half-sample offsets.
    const PoseSample pose{log.nearestAlongSmoothed(C::kX, q), log.nearestAlongSmoothed(C::kY, q),
                          log.nearestAlongSmoothed(C::kPsi, q), log.at(C::kXDot, q), log.at(C::kYDot, q),
                          log.at(C::kYawRate, q)};
    trace.t.push_back(t);
    trace.measured.push_back(log.samples(C::kDeltaDes)[i]);
    trace.predicted.push_back(tracker.command(pose, t).delta_des);  // the excitation runs on log time
  }
  out.traces.push_back(std::move(trace));
  return out;
}

}  // namespace lane_keeping
