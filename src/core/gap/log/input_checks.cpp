// Input checks of a log before its diagnosis (input_checks.h; thresholds and reasons in docs/gap.md, "Inputs").
#include "lane_keeping/gap/log/input_checks.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/printf_string.h"
#include "lane_keeping/gap/log/heading_agreement.h"
#include "lane_keeping/gap/log/straight_line_steering.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/tire/tire.h"

namespace lane_keeping {
namespace {

// ---- thresholds (docs/gap.md, "Inputs", says why each) ------------------------------------------
constexpr std::size_t kListedHoles = 10;  ///< holes listed one by one; the rest in one entry
constexpr double kMaxStep = 0.5;          ///< [s] a median step beyond it: no car log is sampled this slowly
constexpr double kRefusedSpan = 1000.0;   ///< [s] ... and a span beyond it: every noise-only draw simulates hours
/// A channel is stuck when it moves less than this fraction of what a channel tied to it implies.
constexpr double kStuckFraction = 0.01;
/// A ratio of a channel's motion to what its partner implies beyond this: a units or scale error.
constexpr double kUnitsRatio = 8.0;
/// Two channels that should move alike moving this many times apart: a unit between them (steer ratio, degrees).
constexpr double kUnitFactor = 11.0;
constexpr double kDegrees = 180.0 / M_PI;
constexpr double kSpeedMismatch = 0.25;  ///< logged median speed vs vehicle.speed, relative
constexpr double kMaxLateralAcceleration = 20.0;  ///< [m/s^2] 2 g: beyond what any road tire sustains
/// Motion a partner must imply before a stuck channel counts (well above a straight road's noise).
constexpr double kSteeringMotion = 2e-3;   ///< [rad] 0.11 degrees of road-wheel angle
constexpr double kYawMotion = 0.01;        ///< [rad/s]
constexpr double kHeadingMotion = 0.02;    ///< [rad]
constexpr double kLateralMotion = 0.1;     ///< [m/s^2]
constexpr double kTorqueMotion = 0.5;      ///< [N m]
constexpr double kDerivativeWindow = 0.1;  ///< [s] half-width of the smoothed derivatives compared here

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

double spread(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean(v);
  double ss = 0.0;
  for (double x : v) ss += (x - m) * (x - m);
  return std::sqrt(ss / static_cast<double>(v.size()));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

/// A channel tied to the one checked, and the motion it implies for it (in the checked channel's units).
struct Partner {
  std::string what;        ///< e.g. "the yaw rate (l yaw_rate / V)"
  double expected = 0.0;   ///< RMS motion it implies
  double noise = 0.0;      ///< the white noise of that implied series
  double floor = 0.0;      ///< motion below which it shows nothing
};

class Checker {
 public:
  Checker(const GapLog& log, const SimConfig& config) : log_(log), config_(config) {
    const std::size_t n = log.size();
    speed_.assign(n, std::max(1.0, std::fabs(config.vehicle.speed)));
    if (log.hasSpeed()) {
      for (std::size_t i = 0; i < n; ++i) speed_[i] = std::max(1.0, std::fabs(log.v[i]));
    }
    typical_speed_ = median(speed_);
    step_ = log.medianStep();
  }

  std::vector<InputCheck> run() {
    if (log_.size() < 2 || !(step_ > 0.0)) return out_;
    timeAxis();
    holes();
    rates();
    // A time axis in another unit makes every derivative, integral and distance wrong by its factor: the
    // checks built on them would name a "stuck localisation" or a unit where the time is at fault.
    if (flagged("t")) return out_;
    speedUnits();
    stuckChannels();
    units();
    speed();
    headings();
    return out_;
  }

 private:
  double since(double t) const { return t - log_.t.front(); }
  bool has(const char* name) const { return log_.has(name); }
  bool scaled(const char* name) const { return log_.has(name, true); }
  bool flagged(const std::string& channel) const {
    return std::any_of(out_.begin(), out_.end(), [&](const InputCheck& c) {
      return c.channel == channel && (c.kind == "stuck" || c.kind == "units");
    });
  }
  InputCheck& add(const std::string& channel, const std::string& kind, const std::string& detail) {
    out_.push_back(inputCheck(log_.source, channel, kind, detail));
    return out_.back();
  }
  std::vector<double> derivative(const std::vector<double>& v) const {
    return smoothedDerivative(log_.t, v, std::max(kDerivativeWindow, 2.5 * step_), 1);
  }
  /// values[i] * factor(i)
  template <typename F>
  std::vector<double> scaledBy(const std::vector<double>& values, F factor) const {
    std::vector<double> out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) out[i] = values[i] * factor(i);
    return out;
  }
  Partner partner(const std::string& what, const std::vector<double>& implied, double floor) const {
    return {what, spread(implied), fourthDifferenceNoise(implied), floor};
  }

  // ---- time: units and span ----------------------------------------------------------------------
  void timeAxis() {
    if (step_ <= kMaxStep) return;
    const double span = log_.duration();
    const char* unit = step_ < 200.0 ? "milliseconds" : (step_ < 2e5 ? "microseconds" : "nanoseconds");
    const char* key = step_ < 200.0 ? "ms" : (step_ < 2e5 ? "us" : "ns");
    add("t", "units",
        printfString("a median step of %.3g s (%.3g Hz) over %.4g s: no car log is sampled this slowly; the time column "
               "looks like %s (log mapping: `log: time: {unit: %s}`)",
               step_, 1.0 / step_, span, unit, key));
    if (span > kRefusedSpan) {
      add("t", "span",
          printfString("refused: read as seconds, the log spans %.4g s (%.2g h) at %.3g Hz: each noise-only draw would "
                 "simulate the closed loop over all of it, and no replay can run at that rate; if the time column "
                 "is in %s, say so in the log mapping: `log: time: {unit: %s}`",
                 span, span / 3600.0, 1.0 / step_, unit, key))
          .refuse = true;
    }
  }

  // ---- holes ---------------------------------------------------------------------------------------
  void holes() {
    const std::vector<TimeHole> found = timeHoles(log_);
    double rest = 0.0;
    for (std::size_t k = 0; k < found.size(); ++k) {
      const TimeHole& h = found[k];
      if (k >= kListedHoles) {
        rest += h.t1 - h.t0;
        continue;
      }
      InputCheck& c = add("t", "hole",
                          printfString("no samples for %.3g s (%.0f median steps) from %.4g s to %.4g s after the log's "
                                 "start: the replays start again after it instead of integrating across it",
                                 h.t1 - h.t0, (h.t1 - h.t0) / step_, since(h.t0), since(h.t1)));
      c.t0 = h.t0;
      c.t1 = h.t1;
    }
    if (found.size() > kListedHoles) {
      add("t", "hole",
          printfString("%zu more holes (%.3g s in all), handled alike", found.size() - kListedHoles, rest));
    }
  }

  // ---- sample rate against each subsystem's band ---------------------------------------------------
  void rates() {
    const double rate = 1.0 / step_, nyquist = 0.5 * rate;
    // The time axis' own finding, where it explains the rate (a log in ms reads 1000 times slower).
    std::string time_hint;
    for (const InputCheck& c : out_) {
      if (c.channel == "t" && c.kind == "units") time_hint = " (" + c.detail + ")";
    }
    if (scaled("torque")) {  // the steering and actuator replays both read the torque, in known units
      const Modes m = steeringLoopModes(config_);
      if (m.slow > 0.0 && nyquist < m.slow) {
        add("t", "rate",
            printfString("at %.3g Hz (Nyquist %.3g Hz) the steering loop's modes (%.3g and %.3g Hz: J_F s^2 + k_d s + k_p = "
                   "0, p = %g) are not sampled: the steering and actuator replays cannot resolve the loop and are "
                   "skipped%s",
                   rate, nyquist, m.slow, m.fast, config_.actuator.p, time_hint.c_str()))
            .skip = {"steering", "actuator"};
      } else if (m.fast > 0.0 && nyquist < m.fast) {
        add("t", "rate",
            printfString("at %.3g Hz (Nyquist %.3g Hz) the steering loop's fast mode (%.3g Hz; the slow one %.3g Hz) is "
                   "aliased: the steering and actuator replays cannot resolve effects that act there (a compliant "
                   "column, a short actuation delay)",
                   rate, nyquist, m.fast, m.slow));
      }
    }
    if (has("delta")) {
      const Modes m = chassisModes(config_, typical_speed_);
      if (m.slow > 0.0 && nyquist < m.slow) {
        add("t", "rate",
            printfString("at %.3g Hz (Nyquist %.3g Hz) the chassis' modes at %.3g m/s (%.3g and %.3g Hz: the linear "
                   "single-track model) are not sampled: the chassis replay is skipped%s",
                   rate, nyquist, typical_speed_, m.slow, m.fast, time_hint.c_str()))
            .skip = {"chassis"};
      } else if (m.fast > 0.0 && nyquist < m.fast) {
        add("t", "rate",
            printfString("at %.3g Hz (Nyquist %.3g Hz) the chassis' fast mode at %.3g m/s (%.3g Hz) is aliased: the chassis "
                   "replay cannot resolve effects that act there (tire lag)",
                   rate, nyquist, typical_speed_, m.fast));
      }
    }
    const double tau1 = config_.delays.pose_to_tracker;
    if (has("delta_des") && tau1 > 0.0 && step_ > tau1) {
      add("t", "rate",
          printfString("a step of %.3g s is longer than the tracker's delay tau1 = %.3g s: the tracker replay cannot resolve "
                 "the delay it applies and is skipped%s",
                 step_, tau1, time_hint.c_str()))
          .skip = {"tracker"};
    } else if (has("delta_des") && tau1 > 0.0 && step_ > 0.5 * tau1) {
      add("t", "rate",
          printfString("a step of %.3g s is more than half the tracker's delay tau1 = %.3g s: the tracker replay resolves a "
                 "sensing delay only to about a step",
                 step_, tau1));
    }
  }

  // ---- stuck channels -------------------------------------------------------------------------------
  /// `channel` moves less than kStuckFraction of what the strongest moving partner implies.
  void stuck(const std::string& channel, const char* unit, const std::vector<double>& values,
             const std::vector<Partner>& partners) {
    const Partner* best = nullptr;
    for (const Partner& p : partners) {
      if (p.expected > std::max(p.floor, 3.0 * p.noise) && (best == nullptr || p.expected > best->expected)) best = &p;
    }
    if (best == nullptr) return;
    const double moved = spread(values);
    if (moved >= kStuckFraction * best->expected) return;
    const double lo = *std::min_element(values.begin(), values.end());
    const double hi = *std::max_element(values.begin(), values.end());
    const std::string held = lo == hi ? printfString("constant at %.6g %s", lo, unit)
                                      : printfString("nearly constant (%.6g to %.6g %s, RMS %.3g)", lo, hi, unit, moved);
    add(channel, "stuck",
        printfString("%s is %s while %s implies it moves by %.3g %s RMS: a stuck sensor; every replay that reads %s is "
               "skipped",
               channel.c_str(), held.c_str(), best->what.c_str(), best->expected, unit, channel.c_str()))
        .unusable = true;
  }

  void stuckChannels() {
    const double l = config_.vehicle.wheelbase;
    const auto& t = log_.t;
    if (has("delta")) {
      std::vector<Partner> p;
      if (has("yaw_rate")) {
        p.push_back(partner("the yaw rate (l yaw_rate / V)",
                            scaledBy(log_.yaw_rate, [&](std::size_t i) { return l / speed_[i]; }), kSteeringMotion));
      }
      if (has("delta_des")) p.push_back(partner("delta_des", log_.delta_des, kSteeringMotion));
      stuck("delta", "rad", log_.delta, p);
    }
    if (has("delta_des") && has("delta") && !flagged("delta")) {
      stuck("delta_des", "rad", log_.delta_des, {partner("delta", log_.delta, kSteeringMotion)});
    }
    if (has("yaw_rate")) {
      std::vector<Partner> p;
      if (has("delta") && !flagged("delta")) {
        p.push_back(partner("the steering angle (V delta / l)",
                            scaledBy(log_.delta, [&](std::size_t i) { return speed_[i] / l; }), kYawMotion));
      }
      if (has("psi")) p.push_back(partner("the heading (d psi / dt)", derivative(log_.psi), kYawMotion));
      stuck("yaw_rate", "rad/s", log_.yaw_rate, p);
    }
    if (has("psi") && has("yaw_rate") && !flagged("yaw_rate")) {
      std::vector<double> turned(t.size(), 0.0);  // the integral of the yaw rate
      for (std::size_t i = 1; i < t.size(); ++i) {
        turned[i] = turned[i - 1] + 0.5 * (log_.yaw_rate[i] + log_.yaw_rate[i - 1]) * (t[i] - t[i - 1]);
      }
      stuck("psi", "rad", log_.psi, {partner("the integrated yaw rate", turned, kHeadingMotion)});
    }
    if (has("ay") && has("yaw_rate") && !flagged("yaw_rate")) {
      stuck("ay", "m/s^2", log_.ay,
            {partner("V yaw_rate", scaledBy(log_.yaw_rate, [&](std::size_t i) { return speed_[i]; }), kLateralMotion)});
    }
    if (has("delta_rate") && has("delta") && !flagged("delta")) {
      stuck("delta_rate", "rad/s", log_.delta_rate, {partner("d delta / dt", derivative(log_.delta), kYawMotion)});
    }
    if (has("torque")) {
      std::vector<Partner> p;
      if (scaled("torque") && has("delta_des") && has("delta")) {
        std::vector<double> command(t.size());
        for (std::size_t i = 0; i < t.size(); ++i) {
          command[i] = config_.actuator.kp() * (log_.delta_des[i] - log_.delta[i]);
        }
        p.push_back(partner("the actuator's error (k_p (delta_des - delta))", command, kTorqueMotion));
      }
      const double lo = *std::min_element(log_.torque.begin(), log_.torque.end());
      const double hi = *std::max_element(log_.torque.begin(), log_.torque.end());
      if (lo == hi && has("delta") && spread(log_.delta) > kSteeringMotion) {
        // Exactly constant while the wheel turns: in any unit, no steering torque does that.
        add("torque", "stuck",
            printfString("torque is constant at %.6g while the steering angle moves by %.3g rad RMS: a stuck signal; every "
                   "replay that reads torque is skipped",
                   lo, spread(log_.delta)))
            .unusable = true;
      } else {
        stuck("torque", scaled("torque") ? "N m" : "(bus units)", log_.torque, p);
      }
    }
    if (has("x") && has("y") && log_.hasSpeed()) {
      const double travelled = mean(speed_) * log_.duration();
      const double moved = std::hypot(*std::max_element(log_.x.begin(), log_.x.end()) -
                                          *std::min_element(log_.x.begin(), log_.x.end()),
                                      *std::max_element(log_.y.begin(), log_.y.end()) -
                                          *std::min_element(log_.y.begin(), log_.y.end()));
      if (travelled > 10.0 && moved < kStuckFraction * travelled) {
        for (const char* c : {"x", "y"}) {
          add(c, "stuck",
              printfString("the position moves %.3g m while the logged speed covers %.4g m: a stuck localisation; every "
                     "replay that reads %s is skipped",
                     moved, travelled, c))
              .unusable = true;
        }
      }
    }
  }

  // ---- units -----------------------------------------------------------------------------------------
  void units() {
    const double l = config_.vehicle.wheelbase;
    // Heading against the yaw rate: one of them in degrees moves 57.3 times the other.
    if (has("psi") && has("yaw_rate") && !flagged("psi") && !flagged("yaw_rate")) {
      const double rate = spread(log_.yaw_rate), heading_rate = spread(derivative(log_.psi));
      if (rate > kYawMotion && heading_rate > kYawMotion) {
        const double ratio = heading_rate / rate;
        if (ratio > kDegrees / 3.0 && ratio < kDegrees * 3.0) {
          add("psi", "units",
              printfString("d psi / dt moves %.3g times the yaw rate: psi looks like degrees (57.3); check its unit, or its "
                     "scale in the log mapping",
                     ratio));
        } else if (ratio < 3.0 / kDegrees && ratio > 1.0 / (3.0 * kDegrees)) {
          add("yaw_rate", "units",
              printfString("the yaw rate moves %.3g times d psi / dt: it looks like degrees per second (57.3); check its "
                     "unit, or its scale in the log mapping",
                     1.0 / ratio));
        }
      }
    }
    // Heading against the course over ground, where no yaw rate tells.
    if (has("psi") && has("x") && has("y") && !has("yaw_rate") && !flagged("psi")) {
      const std::vector<double> vx = derivative(log_.x), vy = derivative(log_.y);
      std::vector<double> course, heading;
      double previous = 0.0, shift = 0.0;
      for (std::size_t i = 0; i < vx.size(); ++i) {
        if (std::hypot(vx[i], vy[i]) < 2.0) continue;
        double c = std::atan2(vy[i], vx[i]) + shift;
        if (!course.empty()) {
          while (c - previous > M_PI) c -= 2.0 * M_PI, shift -= 2.0 * M_PI;
          while (c - previous < -M_PI) c += 2.0 * M_PI, shift += 2.0 * M_PI;
        }
        previous = c;
        course.push_back(c);
        heading.push_back(log_.psi[i]);
      }
      const double turned = spread(course);
      if (course.size() > 10 && turned > 0.05) {
        const double ratio = spread(heading) / turned;
        if (ratio > kDegrees / 3.0 && ratio < kDegrees * 3.0) {
          add("psi", "units",
              printfString("psi moves %.3g times the course over ground (from x, y): it looks like degrees (57.3); check its "
                     "unit, or its scale in the log mapping",
                     ratio));
        }
      }
    }
    // Steering angle against the yaw rate: kinematically delta = l yaw_rate / V, understeer makes it 1-3 times.
    if (has("delta") && !flagged("delta")) {
      bool said = false;
      if (has("yaw_rate") && !flagged("yaw_rate")) {
        const std::vector<double> implied = scaledBy(log_.yaw_rate, [&](std::size_t i) { return l / speed_[i]; });
        const double expected = spread(implied);
        if (expected > kSteeringMotion) {
          const double ratio = spread(log_.delta) / expected;
          if (ratio > kUnitsRatio) {
            add("delta", "units",
                printfString("delta moves %.3g times what the yaw rate implies (l yaw_rate / V; understeer makes it 1-3 "
                       "times): a road-wheel angle in degrees would move 57-170 times, a steering-wheel angle (steer "
                       "ratio ~15) 10-50 times; check its unit, or its scale in the log mapping",
                       ratio));
            said = true;
          }
        }
      }
      // Without a yaw rate, the angle itself: the kinematic lateral acceleration V^2 delta / l it asks for
      // over the log's moving samples (95th percentile: a saturating transient of a real run asks for more
      // at a few samples, which the tires then do not give).
      if (!said && !(has("yaw_rate") && !flagged("yaw_rate"))) {
        std::vector<double> asked;
        for (std::size_t i = 0; i < log_.size(); ++i) {
          if (speed_[i] >= 5.0) asked.push_back(speed_[i] * speed_[i] * std::fabs(log_.delta[i]) / l);
        }
        if (asked.size() >= 10) {
          const std::size_t k = asked.size() * 95 / 100;
          std::nth_element(asked.begin(), asked.begin() + static_cast<std::ptrdiff_t>(k), asked.end());
          if (asked[k] > kMaxLateralAcceleration) {
            add("delta", "units",
                printfString("delta asks for a kinematic lateral acceleration V^2 delta / l of %.3g m/s^2 or more in 5 %% "
                       "of the moving samples, beyond any tire's %.0f m/s^2: it looks like degrees or a "
                       "steering-wheel angle; check its unit, or its scale in the log mapping",
                       asked[k], kMaxLateralAcceleration));
          }
        }
      }
    }
    // Desired against measured steering angle: the actuator makes one follow the other.
    if (has("delta_des") && has("delta") && !flagged("delta") && !flagged("delta_des")) {
      const double measured = spread(log_.delta), desired = spread(log_.delta_des);
      if (measured > kSteeringMotion && desired > kSteeringMotion) {
        // (A factor of a unit: a steer ratio of 11-20, or 57.3; a steering loop that saturates or oscillates
        // moves the wheel several times its command, a torque-limited lane change 8.5 times.)
        const double ratio = desired / measured;
        if (ratio > kUnitFactor || ratio < 1.0 / kUnitFactor) {
          add("delta_des", "units",
              printfString("delta_des moves %.3g times delta, which the actuator makes follow it: one of the two is in other "
                     "units (a steering-wheel angle: 11-20 times, degrees: 57); check their units, or their scales in "
                     "the log mapping",
                     ratio));
        }
      }
    }
    // Lateral acceleration against V yaw_rate (the steady-state a_y).
    if (has("ay") && has("yaw_rate") && !flagged("ay") && !flagged("yaw_rate")) {
      const double expected = spread(scaledBy(log_.yaw_rate, [&](std::size_t i) { return speed_[i]; }));
      if (expected > 3.0 * kLateralMotion) {
        const double ratio = spread(log_.ay) / expected;
        if (ratio > 1.0 / 20.0 && ratio < 1.0 / 5.0) {
          add("ay", "units",
              printfString("ay moves %.3g times V yaw_rate: it looks like g (1 / 9.81); check its unit, or its scale in the "
                     "log mapping",
                     ratio));
        }
      }
    }
  }

  /// Speed against the speed of the pose; a speed in km/h or mph is not used for V by the other checks.
  void speedUnits() {
    if (!log_.hasSpeed() || !has("x") || !has("y")) return;
    const std::vector<double> vx = derivative(log_.x), vy = derivative(log_.y);
    std::vector<double> pose_speed(vx.size());
    for (std::size_t i = 0; i < vx.size(); ++i) pose_speed[i] = std::hypot(vx[i], vy[i]);
    const double moving = median(pose_speed);
    if (!(moving > 2.0)) return;
    const double ratio = median(log_.v) / moving;
    const char* unit = ratio > 3.0 && ratio < 4.3 ? "km/h (3.6)" : (ratio > 1.9 && ratio < 2.6 ? "mph (2.24)" : "");
    if (!*unit) return;
    add("v", "units",
        printfString("v is %.3g times the speed of the logged position: it looks like %s; check its unit, or its scale in "
               "the log mapping",
               ratio, unit));
    speed_.assign(log_.size(), std::max(1.0, std::fabs(config_.vehicle.speed)));
    typical_speed_ = speed_.front();
  }

  // ---- the gyro, psi and ay / V laid over each other (heading_agreement.h); the steering on the straights --
  void headings() {
    // A channel already found stuck or in another unit is what is wrong with it; its scale means nothing.
    for (const char* channel : {"yaw_rate", "psi", "ay", "v"}) {
      if (flagged(channel)) return;
    }
    for (InputCheck& c : headingAgreementChecks(log_)) out_.push_back(std::move(c));
    // The steering angle at which the car goes straight (straight_line_steering.h), the gyro's measured drift
    // taken out of the path's curvature first.
    if (flagged("delta")) return;
    double bias = 0.0;
    for (const MeasuredSensorError& e : measuredSensorErrors({&log_})) {
      if (e.key == "sensors.yaw_rate_bias") bias = e.value;
    }
    for (InputCheck& c : straightLineSteeringChecks(log_, config_.vehicle.wheelbase, bias)) out_.push_back(std::move(c));
  }

  // ---- speed -----------------------------------------------------------------------------------------
  void speed() {
    if (!log_.hasSpeed() || flagged("v")) return;
    std::size_t not_moving = 0;
    double first = 0.0;
    for (std::size_t i = 0; i < log_.size(); ++i) {
      if (log_.v[i] <= 0.0) {
        if (not_moving++ == 0) first = since(log_.t[i]);
      }
    }
    if (not_moving > 0) {
      add("v", "speed",
          printfString("v <= 0 in %zu of %zu samples (the first %.4g s after the start): the model's slip angles divide by "
                 "V (Beregi eq 8), so the replays that take V from the log mean nothing there",
                 not_moving, log_.size(), first));
    }
    const double logged = median(log_.v), configured = config_.vehicle.speed;
    if (configured > 0.0 && std::fabs(logged / configured - 1.0) > kSpeedMismatch) {
      const double lo = *std::min_element(log_.v.begin(), log_.v.end());
      const double hi = *std::max_element(log_.v.begin(), log_.v.end());
      add("v", "speed",
          printfString("the logged speed (median %.3g, %.3g to %.3g m/s) is %.0f %% off vehicle.speed = %.3g m/s: the replays "
                 "and the closed-loop runs (noise-only null, closed-loop checks, how far) follow a logged speed that "
                 "varies, but drive at vehicle.speed where it does not; set it in the run's scenario",
                 logged, lo, hi, 100.0 * (logged / configured - 1.0), configured));
    }
  }

  const GapLog& log_;
  const SimConfig& config_;
  std::vector<double> speed_;  ///< [m/s] per sample: |v| (at least 1) where logged, else vehicle.speed
  double typical_speed_ = 0.0;
  double step_ = 0.0;
  std::vector<InputCheck> out_;
};

Modes modesOf(double a11, double a12, double a21, double a22) {
  const double tr = a11 + a22, det = a11 * a22 - a12 * a21;
  const std::complex<double> root = std::sqrt(std::complex<double>(0.25 * tr * tr - det, 0.0));
  const double first = std::abs(0.5 * tr + root), second = std::abs(0.5 * tr - root);
  return {std::min(first, second) / (2.0 * M_PI), std::max(first, second) / (2.0 * M_PI)};
}

}  // namespace

Modes steeringLoopModes(const SimConfig& config) {
  const double J = config.vehicle.steering_inertia, kp = config.actuator.kp(), kd = config.actuator.kd();
  if (!(J > 0.0) || !(kp > 0.0)) return {};
  // J s^2 + kd s + kp = 0, as the 2x2 system [0 1; -kp/J -kd/J].
  return modesOf(0.0, 1.0, -kp / J, -kd / J);
}

Modes chassisModes(const SimConfig& config, double speed) {
  const VehicleParams& v = config.vehicle;
  const double V = std::max(1.0, std::fabs(speed));
  const double a = v.cgToFrontAxle(), b = v.cg_to_rear_axle, m = v.mass, J = v.yaw_inertia;
  const double cf = createTire(config.tire_front, v.frontAxleLoad()).corneringStiffness();
  const double cr = createTire(config.tire_rear, v.rearAxleLoad()).corneringStiffness();
  if (!(cf > 0.0) || !(cr > 0.0) || !(m > 0.0) || !(J > 0.0)) return {};
  // Lateral velocity and yaw rate of the linear single track (small slip angles, F_y = C alpha).
  return modesOf(-(cf + cr) / (m * V), -V - (a * cf - b * cr) / (m * V), -(a * cf - b * cr) / (J * V),
                 -(a * a * cf + b * b * cr) / (J * V));
}

InputCheck inputCheck(const std::string& log, const std::string& channel, const std::string& kind,
                      const std::string& detail) {
  InputCheck c;
  c.log = log;
  c.channel = channel;
  c.kind = kind;
  c.detail = detail;
  return c;
}

std::vector<InputCheck> inputChecks(const GapLog& log, const SimConfig& config) { return Checker(log, config).run(); }

void refuseImplausibleLog(const std::vector<InputCheck>& checks) {
  for (const InputCheck& c : checks) {
    if (c.refuse) throw InputError(c.log + ": column '" + c.channel + "': " + c.detail);
  }
}

}  // namespace lane_keeping
