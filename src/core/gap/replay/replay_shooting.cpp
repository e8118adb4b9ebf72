#include "lane_keeping/gap/replay/replay_shooting.h"

#include <cmath>
#include <limits>
#include <variant>

#include "lane_keeping/sim/model_factory.h"

namespace lane_keeping {
namespace replay {

/// Largest RK4 step that resolves a tire's fastest dynamics at `speed`: its relaxation lag
/// (relaxation length / V), the lumped LuGre transport (~ a / V) or, for the distributed tread, the
/// transport across one bristle spacing (L / (N - 1) / V: 0.34 ms at 40 bristles and 15 m/s; the
/// replays' 2-4 ms steps made a distributed tire blow up).
double tireStep(const Tire& tire, double speed) {
  double step = std::numeric_limits<double>::infinity();
  if (tire.relaxationLength() > 0.0) step = std::min(step, 0.5 * tire.relaxationLength() / speed);
  if (const auto* distributed = std::get_if<LugreDistributedTire>(&tire.model())) {
    step = std::min(step, distributed->coefficients().contact_length / (distributed->bristles() - 1) / speed);
  } else if (tire.stateSize() > 0 && tire.name() != "brush" && tire.name() != "magic_formula") {
    step = std::min(step, 0.5 * tire.contactHalfLength() / speed);
  }
  return step;
}

/// Normalisation of an output: RMS about its mean over the whole log (never below a tiny floor).
double scaleOf(const std::vector<double>& v) {
  double mean = 0.0;
  for (double x : v) mean += x;
  mean /= std::max<std::size_t>(1, v.size());
  double sum = 0.0;
  for (double x : v) sum += (x - mean) * (x - mean);
  const double s = v.empty() ? 0.0 : std::sqrt(sum / v.size());
  return std::max(s, 1e-9);
}

bool inSegments(double t, const std::vector<TimeSegment>& segments) {
  for (const auto& s : segments) {
    if (t >= s.t0 && t < s.t1) return true;
  }
  return false;
}

ReplayTrace makeTrace(const std::string& name, const std::vector<double>& measured_all) {
  ReplayTrace trace;
  trace.name = name;
  trace.scale = scaleOf(measured_all);
  return trace;
}

/// Shooting intervals [a, b) covering the segments.
std::vector<TimeSegment> shootingIntervals(const std::vector<TimeSegment>& segments, double horizon) {
  std::vector<TimeSegment> out;
  for (const auto& s : segments) {
    for (double a = s.t0; a < s.t1 - 1e-9; a += horizon) out.push_back({a, std::min(a + horizon, s.t1)});
  }
  return out;
}

/// Noise level used for weighting: the estimate, but never below a small fraction of the scale (a
/// noise-free simulated log must not divide by zero).
double noiseFor(const LogSignals& log, LogSignals::Channel c, double scale) {
  return std::max(log.noise(c), 1e-6 * scale);
}

SingleTrackModel replayModel(const SimConfig& config, const LogSignals& log) {
  if (!log.speedVaries()) return createVehicleModel(config);
  SimConfig c = config;
  c.vehicle.speed_variation = 0.0;
  c.vehicle.speed_profile = {};
  return createVehicleModel(c);
}

void imposeLoggedSpeed(SingleTrackModel& model, const LogSignals& log, double t, std::size_t* hint) {
  if (!log.speedVaries()) {
    model.followSpeedProfile(t - log.start());  // a scenario's profile in time, if any: the run's t = 0 is the log's start
    return;
  }
  const LogSignals::Position here = log.positionAt(t, hint);
  model.setSpeed(log.at(LogSignals::kSpeed, here), log.at(LogSignals::kSpeedRate, here));
}

}  // namespace replay
}  // namespace lane_keeping
