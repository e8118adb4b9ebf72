#pragma once
/// Run settings: integration step, duration, initial state, logging, divergence limits.
#include <cmath>
#include <cstdio>
#include <string>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct InitialState {
  double x = 0.0, y = 1.0, psi = 0.0, delta = 0.0;     ///< [m, m, rad, rad]
  double sigma1 = 0.0, sigma2 = 0.0, sigma3 = 0.0;     ///< [m/s, rad/s, rad/s]
};

struct DivergenceLimits {
  double max_lateral_offset = 20.0;  ///< |e_y| [m]
  double max_heading_error = 1.5;    ///< |e_psi| [rad]: beyond ~pi/2 the car is spinning out
  double max_steering_angle = 1.2;   ///< |delta| [rad]: eqs 2-5 are singular at pi/2
};

struct SimulationParams {
  static constexpr double kMaxLogRows = 2e7;
  static constexpr double kMaxPlantSteps = 1e10;

  std::string name = "default";
  std::string description = "Beregi et al. parameters, lumped LuGre tires, straight lane, 1 m offset";
  double step = 1e-4;        ///< plant RK4 step [s]
  double duration = 10.0;    ///< [s]
  double log_rate = 1000.0;  ///< CSV rows per second [Hz]
  double settling_fraction = 0.02;  ///< settled when |e_y| stays below this fraction of its peak
  InitialState initial;
  DivergenceLimits divergence;

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.choice(prefix + "name", name, {}, "scenario name (free text, printed in the summary)");
    v.choice(prefix + "description", description, {}, "one-line description (free text)");
    v.number(prefix + "step", step, "s", Range::closed(1e-8, 1e-2), "fixed RK4 step of the vehicle plant");
    v.number(prefix + "duration", duration, "s", Range::positive(), "simulated time");
    v.number(prefix + "log_rate", log_rate, "Hz", Range::positive(), "rows per second in the CSV log");
    v.number(prefix + "settling_fraction", settling_fraction, "", Range::open(0.0, 1.0),
             "settling time: |e_y| stays below this fraction of its peak");
    const std::string ip = prefix + "initial.";
    v.number(ip + "x", initial.x, "m", Range::any(), "x of G");
    v.number(ip + "y", initial.y, "m", Range::any(), "y of G");
    v.number(ip + "psi", initial.psi, "rad", Range::closed(-3.2, 3.2), "yaw angle");
    v.number(ip + "delta", initial.delta, "rad", Range::open(-1.5, 1.5), "steering angle");
    v.number(ip + "sigma1", initial.sigma1, "m/s", Range::any(), "lateral velocity of G");
    v.number(ip + "sigma2", initial.sigma2, "rad/s", Range::any(), "yaw rate");
    v.number(ip + "sigma3", initial.sigma3, "rad/s", Range::any(), "steering rate");
    const std::string dp = prefix + "divergence.";
    v.number(dp + "max_lateral_offset", divergence.max_lateral_offset, "m", Range::positive(),
             "stop as diverged when |e_y| exceeds this");
    v.number(dp + "max_heading_error", divergence.max_heading_error, "rad", Range::open(0.0, 3.1416),
             "stop as diverged (spinning out) when |e_psi| exceeds this");
    v.number(dp + "max_steering_angle", divergence.max_steering_angle, "rad", Range::open(0.0, 1.5707),
             "stop as diverged when |delta| exceeds this (eqs 2-5 are singular at pi/2)");
  }

  static std::string gFormat(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
  }

  void validate(const std::string& prefix, std::vector<ConfigProblem>& problems) const {
    if (step > duration) {
      problems.push_back({prefix + "step", "", "is longer than " + prefix + "duration"});
    }
    // Bounds that keep a typo from exhausting memory or running for days (simulation.duration: 1e9 ended
    // in std::bad_alloc): the log is held in memory (~0.3 kB a row), the plant steps at `step`.
    if (duration * log_rate > kMaxLogRows) {
      problems.push_back({prefix + "duration", "",
                          "x " + prefix + "log_rate = " + gFormat(duration * log_rate) + " log rows; at most " +
                              gFormat(kMaxLogRows) + " (about 6 GB in memory): shorten the run or lower the rate"});
    }
    if (duration / step > kMaxPlantSteps) {
      problems.push_back({prefix + "duration", "",
                          "/ " + prefix + "step = " + gFormat(duration / step) + " plant steps; at most " +
                              gFormat(kMaxPlantSteps) + " (hours of computing): shorten the run or lengthen the step"});
    }
    // The plant logs at most one row a step: a higher rate was capped without a word.
    if (step > 0.0 && log_rate * step > 1.0 + 1e-9) {
      problems.push_back({prefix + "log_rate", "",
                          "= " + gFormat(log_rate) + " Hz is above the plant's rate 1 / " + prefix + "step = " +
                              gFormat(1.0 / step) + " Hz; the log holds at most one row per plant step: lower it "
                              "or shorten the step"});
    }
    const double step_ns = step * 1e9;
    if (std::abs(step_ns - 2.0 * std::round(step_ns / 2.0)) > 1e-3) {
      problems.push_back({prefix + "step", "",
                          "must be a whole, even number of nanoseconds (RK4 evaluates the input at mid-step)"});
    }
  }
};

}  // namespace lane_keeping
