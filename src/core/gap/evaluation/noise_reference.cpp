#include "lane_keeping/gap/evaluation/noise_reference.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/time.h"
#include "lane_keeping/gap/log/band_noise.h"
#include "lane_keeping/gap/log/linear_resample.h"
#include "lane_keeping/gap/log/logged_speed.h"
#include "lane_keeping/gap/log/time_holes.h"
#include "lane_keeping/sim/closed_loop.h"

namespace lane_keeping {

void addSensorNoise(GapLog& g, const SensorNoise& n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  // Channels in a fixed order, one unit normal per row each, whatever their character.
  auto add = [&](const char* column, std::vector<double>& v, double sigma) {
    const auto it = n.character.find(column);
    ChannelCharacter c = it != n.character.end() ? it->second : ChannelCharacter{};
    if (it == n.character.end()) c.sigma = sigma;
    addCharacterisedNoise(v, c, rng, unit);
  };
  add("x", g.x, n.position);
  add("y", g.y, n.position);
  add("psi", g.psi, n.heading);
  add("yaw_rate", g.yaw_rate, n.yaw_rate);
  add("delta", g.delta, n.steering);
  add("delta_rate", g.delta_rate, n.steering_rate);
  add("torque", g.torque, n.torque);
  add("ay", g.ay, n.lateral_acceleration);
  add("v", g.v, n.speed);
}

double whiteNoiseLevel(const LogSignals& log, LogSignals::Channel c,
                       const std::vector<std::pair<std::size_t, std::size_t>>& stretches) {
  // White levels from the upper half of each channel's band (band_noise.h): the fourth differences of
  // LogSignals::noise read a steering loop's fast ringing and a start transient as noise (132x the torque
  // noise on a log 1.7 ms from the margin), and draws that noisy hide what the ringing shows. Where a
  // channel is too short for the band's cells, the fourth differences' estimate.
  return log.has(c) ? upperBandNoise(log.samples(c), stretches).value_or(log.noise(c)) : log.noise(c);
}

SensorNoise estimatedNoise(const LogSignals& log, const GapLog* nominal) {
  using C = LogSignals;
  SensorNoise n;
  const auto stretches = holeFreeStretches(log.times());
  auto white = [&](C::Channel c) { return whiteNoiseLevel(log, c, stretches); };
  // x and y share one sensor; the larger estimate is the safer one (a curving path inflates neither much).
  n.position = std::max(white(C::kX), white(C::kY));
  n.heading = white(C::kPsi);
  n.yaw_rate = white(C::kYawRate);
  n.steering = white(C::kDelta);
  n.torque = white(C::kTorque);
  n.steering_rate = log.log().hasSteeringRate() ? white(C::kDeltaRate) : 0.0;
  n.lateral_acceleration = log.log().hasLateralAcceleration() ? white(C::kLateralAcceleration) : 0.0;
  n.speed = log.log().hasSpeed() ? white(C::kSpeed) : 0.0;
  for (auto [column, channel, white] :
       {std::tuple<const char*, C::Channel, double>{"x", C::kX, n.position}, {"y", C::kY, n.position},
        {"psi", C::kPsi, n.heading}, {"yaw_rate", C::kYawRate, n.yaw_rate}, {"delta", C::kDelta, n.steering},
        {"torque", C::kTorque, n.torque}, {"ay", C::kLateralAcceleration, n.lateral_acceleration},
        {"v", C::kSpeed, n.speed}}) {
    if (!log.has(channel)) continue;
    const std::vector<double> model =
        nominal && nominal->column(column) ? linearAt(nominal->t, *nominal->column(column), log.times())
                                           : std::vector<double>{};
    // The body's sensors: their fast content is noise (sensor_character.h).
    const bool body = channel == C::kYawRate || channel == C::kLateralAcceleration;
    const ChannelCharacter c = estimateCharacter(log.samples(channel), white, model, body);
    if (!c.plain()) n.character[column] = c;
  }
  if (log.log().hasSteeringRate()) {
    const ChannelCharacter c = estimateCharacter(log.log().delta_rate, n.steering_rate);
    if (!c.plain()) n.character["delta_rate"] = c;
  }
  return n;
}

GapLog nominalReferenceLog(const SimConfig& nominal, const LogSignals& log) {
  SimConfig c = withLoggedSpeed(nominal, log);  // driving as the car drove, when its speed varies
  const double step = log.log().medianStep();
  // At most a row per plant step (SimulationParams::validate): a log sampled faster than the plant steps
  // is compared with the reference at the plant's rate.
  c.simulation.log_rate = std::min(1.0 / step, 1.0 / c.simulation.step);
  c.simulation.duration = log.end() - log.start() + step;
  // The simulation's t = 0 is the log's start (its times are shifted to the log's below); the excitation
  // runs on the log's t plus the run's own clock offset (excitation_clock.h).
  c.tracker.excitation_clock_offset += log.start();
  const RunResult run = ClosedLoop(c).run();
  if (run.diverged()) {
    throw LaneKeepingError("noise reference for " + log.log().source + ": the nominal closed loop " + run.message);
  }
  GapLog out = gapLogFromRows(run.rows, log.log().source + " (noise reference)");
  // v as the log it stands for holds it: once prepared, V of eq 1 (logged_speed.h), here from the simulated
  // state itself (gapLogFromRows wrote the speed of G and kept the rows whose values are finite).
  if (log.log().speed_of == LoggedSpeed::kFrontAxle) {
    const double b = c.vehicle.cgToFrontAxle();
    std::size_t row = 0;
    for (const LogRow& r : run.rows) {
      if (row < out.t.size() && r.t == out.t[row]) {
        const VehicleStateSample& s = r.state;
        out.v[row++] = frontAxleSpeed(s.speed, s.sigma1, s.sigma2, s.delta, b);
      }
    }
    out.speed_of = LoggedSpeed::kFrontAxle;
  }
  for (double& t : out.t) t += log.start();
  // The reference holds the columns the log holds, in the same units state (a partial log's replays
  // are the ones its columns allow).
  const GapLog& real = log.log();
  for (auto [present, column] : {std::pair<bool, std::vector<double>*>{real.has("x"), &out.x},
                                 {real.has("y"), &out.y}, {real.has("psi"), &out.psi},
                                 {real.has("yaw_rate"), &out.yaw_rate}, {real.has("v"), &out.v},
                                 {real.has("ay"), &out.ay}, {real.has("delta"), &out.delta},
                                 {real.has("delta_rate"), &out.delta_rate}, {real.has("delta_des"), &out.delta_des},
                                 {real.has("torque"), &out.torque}}) {
    if (!present) column->clear();
  }
  out.unscaled = real.unscaled;
  if (real.psi_is_course && !out.psi.empty()) {  // the log's heading is a course: heading plus body slip
    for (std::size_t i = 0; i < out.psi.size() && i < run.rows.size(); ++i) {
      const VehicleStateSample& s = run.rows[i].state;
      out.psi[i] += std::atan2(s.sigma1, std::sqrt(std::max(0.0, s.speed * s.speed - s.sigma1 * s.sigma1)));
    }
    out.psi_is_course = true;
  }
  return out;
}

GapLog noiseReferenceLog(const SimConfig& nominal, const LogSignals& log, unsigned seed) {
  GapLog out = nominalReferenceLog(nominal, log);
  addSensorNoise(out, estimatedNoise(log, &out), seed);
  return out;
}

}  // namespace lane_keeping
