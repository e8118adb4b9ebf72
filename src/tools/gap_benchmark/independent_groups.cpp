#include "gap_benchmark/independent_groups.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {

namespace {

std::string num(double v) { return formatNumber(v); }

/// Adds cases of one group: 20 s runs (as the family's first cases), seeds counted on from 20000.
class GroupBuilder {
 public:
  explicit GroupBuilder(std::vector<BenchmarkCase>& cases) : cases_(cases) {}
  void group(std::string name) { group_ = std::move(name); }

  /// One case; `truth_form` is the channel or placement the verdict must name ("" = any).
  BenchmarkCase& add(const std::string& id, const std::string& category, const std::string& truth,
                     const std::string& truth_form, const std::string& magnitude, const std::string& manoeuvre,
                     std::vector<std::string> overlay, std::vector<std::string> setup, double log_rate = 0.0) {
    setup.insert(setup.begin(), "simulation.duration=20");
    BenchmarkCase c{id, category, truth, magnitude, manoeuvre, std::move(overlay), ++seed_};
    c.setup = std::move(setup);
    c.log_rate = log_rate;
    c.group = group_;
    c.truth_form = truth_form;
    cases_.push_back(std::move(c));
    return cases_.back();
  }
  /// A no-effect log.
  BenchmarkCase& none(const std::string& id, const std::string& manoeuvre, std::vector<std::string> setup,
                      double log_rate = 0.0) {
    return add(id, "none", "none", "", "", manoeuvre, {}, std::move(setup), log_rate);
  }
  /// Two (or more) hidden effects at once: the first is `truth`.
  BenchmarkCase& several(const std::string& id, std::vector<TruthEffect> truths, const std::string& magnitude,
                         const std::string& manoeuvre, std::vector<std::string> overlay, std::vector<std::string> setup,
                         double log_rate = 0.0) {
    BenchmarkCase& c = add(id, "in_list", truths.front().effect, truths.front().form, magnitude, manoeuvre,
                           std::move(overlay), std::move(setup), log_rate);
    c.truths = std::move(truths);
    return c;
  }

 private:
  std::vector<BenchmarkCase>& cases_;
  std::string group_;
  unsigned seed_ = 20000;
};

/// A held-out run on another road (BenchmarkCase::heldout_*).
void heldOutOn(BenchmarkCase& c, const std::string& manoeuvre, std::vector<std::string> setup) {
  c.heldout_manoeuvre = manoeuvre;
  c.heldout_setup = std::move(setup);
}

// ---- Sensor characters of a vehicle bus (sensor_character.h), at the benchmark's white levels.
// Steps as CAN signals have them: a yaw rate in 0.1 deg/s, a steering-wheel angle in 0.1 deg (a road-wheel
// angle of 1.2e-4 rad at a steering ratio of 14.5), a motor torque in 0.5 N m at the kingpin, a lateral
// acceleration in 0.01 m/s^2; messages at 50 Hz (yaw rate, a_y) and 100 Hz (angle, torque).
constexpr double kYawRateStep = 0.1 * M_PI / 180.0;
constexpr double kSteeringStep = 0.1 * M_PI / 180.0 / 14.5;
constexpr double kTorqueStep = 0.5;
constexpr double kAyStep = 0.01;

ChannelCharacter channel(double quantum, int hold, double ar, double sigma) {
  ChannelCharacter c;
  c.quantum = quantum;
  c.hold = std::max(1, hold);
  c.ar = ar;
  c.sigma = sigma;
  return c;
}

/// Rows a message of `message_hz` is held for in a log of `log_hz`.
int holdRows(double log_hz, double message_hz) { return static_cast<int>(std::lround(std::max(1.0, log_hz / message_hz))); }

using Bus = std::map<std::string, ChannelCharacter>;

/// Quantised yaw rate, steering angle, torque and a_y (a new reading every row).
Bus quantisedBus() {
  const SensorNoise w;
  return {{"yaw_rate", channel(kYawRateStep, 1, 0.0, w.yaw_rate)},
          {"delta", channel(kSteeringStep, 1, 0.0, w.steering)},
          {"torque", channel(kTorqueStep, 1, 0.0, w.torque)},
          {"ay", channel(kAyStep, 1, 0.0, w.lateral_acceleration)}};
}

/// Messages slower than the log's rows, resampled by repeating them.
Bus heldBus(double log_hz) {
  const SensorNoise w;
  return {{"yaw_rate", channel(0.0, holdRows(log_hz, 50.0), 0.0, w.yaw_rate)},
          {"ay", channel(0.0, holdRows(log_hz, 50.0), 0.0, w.lateral_acceleration)},
          {"delta", channel(0.0, holdRows(log_hz, 100.0), 0.0, w.steering)},
          {"torque", channel(0.0, holdRows(log_hz, 100.0), 0.0, w.torque)}};
}

/// AR(1)-coloured noise (a sensor's filter, vibration).
Bus colouredBus() {
  const SensorNoise w;
  return {{"yaw_rate", channel(0.0, 1, 0.8, w.yaw_rate)},
          {"ay", channel(0.0, 1, 0.9, w.lateral_acceleration)},
          {"delta", channel(0.0, 1, 0.6, w.steering)},
          {"torque", channel(0.0, 1, 0.5, w.torque)}};
}

/// All three at once, as a vehicle bus gives them.
Bus fullBus(double log_hz) {
  const SensorNoise w;
  return {{"yaw_rate", channel(kYawRateStep, holdRows(log_hz, 50.0), 0.7, w.yaw_rate)},
          {"ay", channel(kAyStep, holdRows(log_hz, 50.0), 0.8, w.lateral_acceleration)},
          {"delta", channel(kSteeringStep, holdRows(log_hz, 100.0), 0.0, w.steering)},
          {"torque", channel(kTorqueStep, holdRows(log_hz, 100.0), 0.5, w.torque)}};
}

Bus busNamed(const std::string& kind, double log_hz) {
  if (kind == "quantised") return quantisedBus();
  if (kind == "held") return heldBus(log_hz);
  if (kind == "coloured") return colouredBus();
  return fullBus(log_hz);
}

// ---- Truth forms shared by several groups (the candidates' family's forms, at other magnitudes).
/// LuGre kingpin friction with a Stribeck peak (Deur eqs 6, 9).
std::vector<std::string> lugreFriction(double coulomb, double breakaway) {
  return {"steering.friction_model=lugre", "steering.coulomb_friction=" + num(coulomb),
          "steering.breakaway_friction=" + num(breakaway), "steering.friction_velocity=0.02",
          "steering.friction_stiffness=2e4"};
}
/// A shorter contact patch (cornering stiffness as a^2, aligning stiffness as a^3).
std::vector<std::string> shorterPatch(double front, double rear) {
  return {"tire.front.contact_half_length=" + num(front), "tire.rear.contact_half_length=" + num(rear)};
}
/// Load in the boot: mass and yaw inertia up, the centre of gravity moved back (Table 1 car).
std::vector<std::string> bootLoad(double yaw_factor, double mass_factor, double cg_back) {
  return {"vehicle.yaw_inertia=" + num(1343.0 * yaw_factor), "vehicle.mass=" + num(1100.0 * mass_factor),
          "vehicle.cg_to_rear_axle=" + num(1.54 - cg_back)};
}
/// A crosswind 0.2 m ahead of G, gusting along the road.
std::vector<std::string> crosswind(double force, double gust) {
  return {"disturbance.lateral_force=" + num(force), "disturbance.yaw_moment=" + num(0.2 * force),
          "disturbance.gust_amplitude=" + num(gust), "disturbance.gust_wavelength=170"};
}
/// A distributed LuGre tread with carcass relaxation.
std::vector<std::string> treadLag(double relaxation_length) {
  return {"tire.front.model=lugre_distributed", "tire.rear.model=lugre_distributed", "tire.front.lugre.bristles=40",
          "tire.rear.lugre.bristles=40", "tire.front.relaxation_length=" + num(relaxation_length),
          "tire.rear.relaxation_length=" + num(relaxation_length)};
}
/// A smooth torque saturation.
std::vector<std::string> softLimit(double limit) {
  return {"steering.saturation=soft", "steering.torque_limit=" + num(limit)};
}
/// Partial sliding: sliding friction lowered more than adhesion.
std::vector<std::string> slipperyRoad(double mu, double mu0) {
  return {"tire.front.mu=" + num(mu), "tire.front.mu0=" + num(mu0), "tire.rear.mu=" + num(mu), "tire.rear.mu0=" + num(mu0)};
}

std::vector<std::string> joined(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The steering-loop margins below are lk_stability's: the critical torque delay (delays.torque_to_plant)
// of the benchmark's nominal is tau2c - 0.1 ms: 3.28 ms at p = 1000, 2.28 ms at p = 1500, 1.73 ms at
// p = 2000, 1.15 ms at p = 3000 (`lk_stability boundary --param delays.torque_to_plant`).

void sensorErrors(GroupBuilder& b) {
  b.group("sensor errors");
  // Each sensor error on two manoeuvres: once with white noise, once through a vehicle bus.
  struct Error {
    std::string name, effect, form, unit_text;
    std::string key;
    double white_value, bus_value;
    std::string white_manoeuvre, bus_manoeuvre, bus;
    std::vector<std::string> white_setup, bus_setup;
  };
  const double deg = M_PI / 180.0;
  const std::vector<Error> errors{
      // A gyro's bias: the RAV4 minute's is -0.0071 rad/s (issue 46).
      {"yaw_rate_offset", "sensor_offset", "yaw_rate", " rad/s", "sensors.yaw_rate_bias", 0.004, -0.007, "lane_change",
       "bend", "quantised", {}, {}},
      // A steering-angle offset of a few tenths of a degree at the road wheel (openpilot's angle offsets).
      {"steering_offset", "sensor_offset", "steering_angle", " rad", "sensors.steering_angle_bias", 0.3 * deg,
       -0.45 * deg, "sinusoid", "bend", "held", {}, {}},
      // An accelerometer tilted by 0.7 / 1.2 deg (g sin(tilt)).
      {"ay_offset", "sensor_offset", "lateral_acceleration", " m/s^2", "sensors.lateral_acceleration_bias", 0.12, -0.2,
       "bend", "lane_change", "coloured", {}, {}},
      // A heading mount of 0.6 / 0.9 deg (the RAV4's: 0.89 deg).
      {"heading_mount", "sensor_offset", "heading", " rad", "sensors.pose_bias_psi", 0.6 * deg, -0.9 * deg, "sinusoid",
       "straight", "full", {}, {"simulation.initial.y=1.5", "tracker.excitation_amplitude=0.004"}},
      // A yaw-rate column logged 0.12 / 0.18 s late (the race car's: 0.21-0.23 s).
      {"yaw_rate_latency", "sensor_latency", "yaw_rate", " s", "sensors.yaw_rate_latency", 0.12, 0.18, "lane_change",
       "sinusoid", "held", {}, {}},
      // A steering-angle sensor 4 / 2.5 ms late; the actuator closes on it, so only a weaker loop survives it
      // (p = 500: diverges from 6 ms; p = 700 from about 4 ms; lk_simulate on the sinusoid).
      {"steering_latency", "sensor_latency", "steering_angle", " s", "sensors.steering_angle_latency", 0.004, 0.0025,
       "bend", "lane_change", "quantised", {"actuator.p=500"}, {"actuator.p=700"}},
      // A gyro whose gain is 0.87 / 0.9 (the race car's: 0.853).
      {"yaw_rate_scale", "sensor_scale", "yaw_rate", "", "sensors.yaw_rate_scale", 0.87, 0.9, "sinusoid", "bend",
       "coloured", {}, {}},
      // A steering ratio 7 / 10 % off the one the log was converted with.
      {"steering_scale", "sensor_scale", "steering_angle", "", "sensors.steering_angle_scale", 1.07, 1.1, "lane_change",
       "sinusoid", "full", {}, {}},
  };
  for (const Error& e : errors) {
    b.add("sensor-" + e.name + "-" + e.white_manoeuvre, "in_list", e.effect, e.form, num(e.white_value) + e.unit_text,
          e.white_manoeuvre, {e.key + "=" + num(e.white_value)}, e.white_setup);
    BenchmarkCase& bus = b.add("sensor-" + e.name + "-" + e.bus_manoeuvre + "-bus_" + e.bus, "in_list", e.effect, e.form,
                               num(e.bus_value) + e.unit_text, e.bus_manoeuvre, {e.key + "=" + num(e.bus_value)},
                               e.bus_setup);
    bus.sensor_character = busNamed(e.bus, 500.0);
  }
  // No effect, through bus-like sensors: the calibrated test's false-alarm rate on such channels.
  struct NoneLog {
    std::string bus, manoeuvre;
    double rate;
    std::vector<std::string> setup;
  };
  const std::vector<NoneLog> none{
      {"quantised", "lane_change", 500.0, {}},
      {"held", "bend", 500.0, {"actuator.p=1250"}},
      {"coloured", "sinusoid", 500.0, {"tracker.k_y=0.08"}},
      {"full", "straight", 500.0, {"simulation.initial.y=-2", "tracker.excitation_amplitude=0.004"}},
      {"quantised", "sinusoid", 100.0, {"actuator.p=750"}},
      {"held", "lane_change", 100.0, {"tracker.k_y=0.03"}},
      {"coloured", "bend", 1000.0, {"actuator.p=1500"}},
      {"full", "bend", 100.0, {"simulation.initial.y=1"}},
  };
  for (std::size_t i = 0; i < none.size(); ++i) {
    const NoneLog& n = none[i];
    BenchmarkCase& c = b.none("sensor-none-bus_" + n.bus + "-" + std::to_string(i + 1) + "-" + n.manoeuvre + "-" +
                                  num(n.rate) + "Hz",
                              n.manoeuvre, n.setup, n.rate);
    c.sensor_character = busNamed(n.bus, n.rate);
  }
  // A sensor error together with a physical effect: both should be named.
  b.several("sensor-yaw_rate_offset+cornering_stiffness-sinusoid", {{"sensor_offset", "yaw_rate"}, {"cornering_stiffness"}},
            "0.005 rad/s; tread k x0.8 / x0.85", "sinusoid",
            {"sensors.yaw_rate_bias=0.005", "tire.front.lateral_stiffness=1.6e6", "tire.rear.lateral_stiffness=1.7e6"}, {});
  b.several("sensor-heading_mount+crosswind-bend", {{"sensor_offset", "heading"}, {"lateral_disturbance"}},
            "0.7 deg; 350 N", "bend", joined({"sensors.pose_bias_psi=" + num(0.7 * deg)}, crosswind(350.0, 0.2)), {});
  b.several("sensor-steering_offset+steering_friction-lane_change",
            {{"sensor_offset", "steering_angle"}, {"steering_friction"}}, "0.35 deg; T_c 3 N m", "lane_change",
            joined({"sensors.steering_angle_bias=" + num(0.35 * deg)}, lugreFriction(3.0, 4.5)), {"actuator.p=1250"});
}

void twoAtOnce(GroupBuilder& b) {
  b.group("two at once");
  // Each a training run and a held-out run on another road (as issue 47's independent sets).
  // Lane change nominal peak torque 67 N m (p = 1000, 20 s): a soft limit at 55 N m with friction.
  heldOutOn(b.several("two-steering_friction+torque_limit-lane_change-bend", {{"steering_friction"}, {"torque_limit"}},
                      "T_c 3 N m; 55 N m", "lane_change", joined(lugreFriction(3.0, 4.5), softLimit(55.0)), {}),
            "bend", {"simulation.initial.y=-1.5", "simulation.duration=18"});
  // A compliant column (wheel-side sensor) and a torque delay of 1 ms: with the column the critical delay
  // is 1.92 ms at p = 700 (1.19 ms at p = 1000, where 1.5 ms diverged), lk_stability boundary.
  heldOutOn(b.several("two-steering_compliance+actuation_delay-sinusoid-lane_change",
                      {{"steering_compliance"}, {"actuation_delay"}}, "k 2500 N m/rad; 1 ms", "sinusoid",
                      {"steering.column_stiffness=2500", "steering.column_damping=15", "steering.column_inertia=0.05",
                       "delays.torque_to_plant=0.001"},
                      {"actuator.p=700"}),
            "lane_change", {"simulation.duration=16"});
  heldOutOn(b.several("two-crosswind+cornering_stiffness-bend-sinusoid", {{"lateral_disturbance"}, {"cornering_stiffness"}},
                      "350 N; a 0.086 / 0.088 m", "bend", joined(crosswind(350.0, 0.2), shorterPatch(0.086, 0.088)), {}),
            "sinusoid", {"simulation.initial.y=0.8"});
  heldOutOn(b.several("two-inertia+tire_lag-lane_change-sinusoid", {{"inertia"}, {"tire_lag"}},
                      "J x1.3, m x1.1; 0.5 m", "lane_change", joined(bootLoad(1.3, 1.1, 0.03), treadLag(0.5)),
                      {"actuator.p=1250"}),
            "sinusoid", {"simulation.duration=17"});
  heldOutOn(b.several("two-road_friction+sensing_delay-sinusoid-bend", {{"road_friction"}, {"sensing_delay"}},
                      "mu 0.55 / 0.7; +50 ms", "sinusoid",
                      joined(slipperyRoad(0.55, 0.7), {"delays.pose_to_tracker=0.25"}), {}),
            "bend", {"simulation.initial.y=1"});
  heldOutOn(b.several("two-pose_bias+inertia-bend-lane_change", {{"pose_bias"}, {"inertia"}},
                      "12 cm + 5 mrad; J x1.35, m x1.1", "bend",
                      joined({"tracker.pose_bias_y=0.12", "tracker.pose_bias_psi=0.005"}, bootLoad(1.35, 1.1, 0.04)),
                      {"tracker.k_y=0.08"}),
            "lane_change", {"simulation.duration=18"});
  heldOutOn(b.several("two-cornering_stiffness+steering_friction-lane_change-sinusoid",
                      {{"cornering_stiffness"}, {"steering_friction"}}, "k x0.75; T_c 3.5 N m", "lane_change",
                      joined({"tire.front.lateral_stiffness=1.5e6", "tire.rear.lateral_stiffness=1.5e6"},
                             lugreFriction(3.5, 5.0)),
                      {"actuator.p=1500"}),
            "sinusoid", {"simulation.initial.y=-0.7"});
  // A banked road and a torque delay of 2 ms, from a 2 m correction on a straight road.
  heldOutOn(b.several("two-road_bank+actuation_delay-straight-bend", {{"lateral_disturbance"}, {"actuation_delay"}},
                      "400 N; 2 ms", "straight",
                      {"disturbance.kind=road_bank", "disturbance.lateral_force=400", "delays.torque_to_plant=0.002"},
                      {"simulation.initial.y=2", "tracker.excitation_amplitude=0.004"}),
            "bend", {"simulation.duration=16"});
}

void startOfLog(GroupBuilder& b) {
  b.group("start of a log");
  // Issue 47 kind 2: a 2 m correction on a straight road saturates a 48 N m limit in the first second
  // (nominal torque RMS 81 N m over the first 0.5 s, 46 N m over the next; after 2 s below 5 N m).
  b.add("start-torque_limit-48Nm-straight-2m", "in_list", "torque_limit", "", "48 N m", "straight", softLimit(48.0),
        {"simulation.initial.y=2", "tracker.excitation_amplitude=0.004"});
  // The same limit, barely touched by the training run (a sinusoid from 0.5 m, peak 34 N m past its first
  // instants), plain in the held-out run's first second.
  heldOutOn(b.add("start-torque_limit-48Nm-pair-sinusoid-straight", "in_list", "torque_limit", "", "48 N m", "sinusoid",
                  softLimit(48.0), {"simulation.initial.y=0.5"}),
            "straight", {"simulation.initial.y=-2", "tracker.excitation_amplitude=0.004", "simulation.duration=15"});
  // A 3 m correction on snow: the tires saturate in the first seconds only.
  b.add("start-road_friction-snow-straight-3m", "in_list", "road_friction", "", "mu 0.35 / 0.45", "straight",
        slipperyRoad(0.35, 0.45), {"simulation.initial.y=-3", "tracker.excitation_amplitude=0.004"});
  // A heading error of 3 deg at the start with a loaded car.
  b.add("start-inertia-straight-heading", "in_list", "inertia", "", "J x1.4, m x1.12", "straight",
        bootLoad(1.4, 1.12, 0.05), {"simulation.initial.y=1", "simulation.initial.psi=0.05", "tracker.excitation_amplitude=0.004"});
  // The column rings after a 2 m step, on a 100 Hz log.
  b.add("start-steering_compliance-straight-2m-100Hz", "in_list", "steering_compliance", "", "k 1800 N m/rad", "straight",
        {"steering.column_stiffness=1800", "steering.column_damping=15", "steering.column_inertia=0.05",
         "steering.column_stiffening_angle=0.03"},
        {"simulation.initial.y=2", "tracker.excitation_amplitude=0.004"}, 100.0);
}

void delaysNearTheMargin(GroupBuilder& b) {
  b.group("delays near the margin");
  // Issue 47 kind 3: +0.9 ms on a 1 kHz log and +1.7 ms on a 100 Hz log, near the critical torque delay
  // (78 % of it at p = 3000 and p = 1500; 87 % for +1.5 ms at p = 2000). A correction at the start rings the
  // steering loop (torque differs from the nominal loop's by 5-10 N m RMS, lk_simulate).
  b.add("margin-actuation_delay-0.9ms-p3000-1kHz-straight", "in_list", "actuation_delay", "", "+0.9 ms (78 %)", "straight",
        {"delays.torque_to_plant=0.0009"}, {"actuator.p=3000", "simulation.initial.y=1", "tracker.excitation_amplitude=0.004"},
        1000.0);
  b.add("margin-actuation_delay-0.9ms-p3000-1kHz-sinusoid", "in_list", "actuation_delay", "", "+0.9 ms (78 %)", "sinusoid",
        {"delays.torque_to_plant=0.0009"}, {"actuator.p=3000", "simulation.initial.y=0.5"}, 1000.0);
  b.add("margin-actuation_delay-1.7ms-p1500-100Hz-straight", "in_list", "actuation_delay", "", "+1.7 ms (75 %)",
        "straight", {"delays.torque_to_plant=0.0017"},
        {"actuator.p=1500", "simulation.initial.y=-1.5", "tracker.excitation_amplitude=0.004"}, 100.0);
  b.add("margin-actuation_delay-1.5ms-p2000-lane_change", "in_list", "actuation_delay", "", "+1.5 ms (87 %)", "lane_change",
        {"delays.torque_to_plant=0.0015"}, {"actuator.p=2000", "simulation.initial.y=0.5"});
  b.none("margin-none-p3000-1kHz-straight", "straight",
         {"actuator.p=3000", "simulation.initial.y=1", "tracker.excitation_amplitude=0.004"}, 1000.0);
  b.none("margin-none-p2000-100Hz-lane_change", "lane_change", {"actuator.p=2000", "simulation.initial.y=0.5"}, 100.0);
}

void onsets(GroupBuilder& b) {
  b.group("onsets");
  // Effects that set in mid-run (a runtime change of the truth at T; the held-out run's at the same time of
  // its own clock): single logs and pairs. Lane changes at 2-7 s and 10.5-15.5 s of the lane_change run.
  auto mid = [&](const std::string& id, const std::string& truth, const std::string& magnitude,
                 const std::string& manoeuvre, double t, std::vector<std::string> overlay,
                 const std::vector<std::string>& changes, std::vector<std::string> setup) -> BenchmarkCase& {
    BenchmarkCase& c = b.add(id, "in_list", truth, "", magnitude, manoeuvre, std::move(overlay), std::move(setup));
    c.onset = t;
    for (const auto& change : changes) c.truth_changes.push_back(num(t) + ":" + change);
    return c;
  };
  // Kingpin friction that sets in (a seizing joint; the tanh law: LuGre's state cannot appear mid-run).
  mid("midrun-steering_friction-t8-lane_change", "steering_friction", "T_c 3.5 N m from 8 s", "lane_change", 8.0,
      {"steering.friction_velocity=0.02"}, {"steering.coulomb_friction=3.5", "steering.viscous_friction=2"}, {});
  // A wet stretch from 10 s.
  mid("midrun-road_friction-t10-sinusoid", "road_friction", "mu 0.5 / 0.6 from 10 s", "sinusoid", 10.0, {},
      {"tire.front.mu=0.5", "tire.front.mu0=0.6", "tire.rear.mu=0.5", "tire.rear.mu0=0.6"}, {});
  // The steering motor derates (thermal protection) before the second lane change.
  mid("midrun-torque_limit-t9-lane_change", "torque_limit", "50 N m from 9 s", "lane_change", 9.0,
      {"steering.saturation=soft"}, {"steering.torque_limit=50"}, {});
  heldOutOn(mid("midrun-crosswind-t9-pair-bend-sinusoid", "lateral_disturbance", "450 N from 9 s", "bend", 9.0, {},
                {"disturbance.lateral_force=450", "disturbance.yaw_moment=90"}, {}),
            "sinusoid", {"simulation.initial.y=0.5"});
  heldOutOn(mid("midrun-cornering_stiffness-t8-pair-sinusoid-lane_change", "cornering_stiffness", "k x0.75 from 8 s",
                "sinusoid", 8.0, {}, {"tire.front.lateral_stiffness=1.5e6", "tire.rear.lateral_stiffness=1.55e6"}, {}),
            "lane_change", {"simulation.duration=18"});
  heldOutOn(mid("midrun-steering_friction-t7-pair-bend-lane_change", "steering_friction", "T_c 4 N m from 7 s", "bend", 7.0,
                {"steering.friction_velocity=0.02"}, {"steering.coulomb_friction=4", "steering.viscous_friction=1.5"},
                {"actuator.p=1250"}),
            "lane_change", {"simulation.initial.y=-0.5"});
}

void varyingSpeed(GroupBuilder& b) {
  b.group("varying speed");
  // The speed varies along the road (vehicle.speed_variation, known to the diagnosis: the set-up), 15 m/s
  // +-20-30 % (a real run's speed changes in time; along the road is what the configuration has).
  auto speed = [](double variation, double wavelength) {
    return std::vector<std::string>{"vehicle.speed_variation=" + num(variation), "vehicle.speed_wavelength=" + num(wavelength)};
  };
  b.add("speedvar-steering_friction-lane_change", "in_list", "steering_friction", "", "T_c 3 N m", "lane_change",
        lugreFriction(3.0, 4.5), speed(0.2, 200.0));
  b.add("speedvar-cornering_stiffness-sinusoid", "in_list", "cornering_stiffness", "", "a 0.086 / 0.089 m", "sinusoid",
        shorterPatch(0.086, 0.089), speed(0.25, 250.0));
  b.add("speedvar-crosswind-bend", "in_list", "lateral_disturbance", "", "400 N", "bend", crosswind(400.0, 0.25),
        speed(0.3, 300.0));
  b.add("speedvar-inertia-sinusoid", "in_list", "inertia", "", "J x1.35, m x1.1", "sinusoid", bootLoad(1.35, 1.1, 0.04),
        speed(0.2, 180.0));
  b.add("speedvar-actuation_delay-lane_change", "in_list", "actuation_delay", "", "2 ms", "lane_change",
        {"delays.torque_to_plant=0.002"}, joined(speed(0.25, 220.0), {"simulation.initial.y=0.5"}));
  b.add("speedvar-sensing_delay-bend", "in_list", "sensing_delay", "", "+60 ms", "bend", {"delays.pose_to_tracker=0.26"},
        speed(0.2, 250.0));
  b.add("speedvar-yaw_rate_offset-sinusoid", "in_list", "sensor_offset", "yaw_rate", "0.005 rad/s", "sinusoid",
        {"sensors.yaw_rate_bias=0.005"}, speed(0.25, 200.0));
  b.none("speedvar-none-1-lane_change", "lane_change", speed(0.25, 230.0));
  b.none("speedvar-none-2-bend", "bend", joined(speed(0.3, 280.0), {"actuator.p=1250"}));
}

void anotherCar(GroupBuilder& b) {
  b.group("another car");
  // The SUV at 25 m/s: a sinusoid of 250 m (the Table 1 car's 120 m would ask 2.6 m/s^2 at 25 m/s), the bend,
  // a straight road from 2 m.
  const std::vector<std::string> sinusoid{"path.sinusoid.wavelength=250"};
  const std::vector<std::string> straight{"simulation.initial.y=2", "tracker.excitation_amplitude=0.004"};
  auto suv = [&](BenchmarkCase& c) -> BenchmarkCase& {
    c.car = suvCar();
    return c;
  };
  // A 20 % stiffness loss (worn or under-inflated tires) and a 20 % inertia change (issue 47 kind 5).
  const std::vector<std::string> softer{"tire.front.lateral_stiffness=1.76e6", "tire.rear.lateral_stiffness=1.76e6"};
  suv(b.add("suv-cornering_stiffness-sinusoid", "in_list", "cornering_stiffness", "", "k x0.8", "sinusoid", softer, sinusoid));
  suv(b.add("suv-cornering_stiffness-bend", "in_list", "cornering_stiffness", "", "k x0.8", "bend", softer, {}));
  suv(b.add("suv-inertia-sinusoid", "in_list", "inertia", "", "J x1.2", "sinusoid", {"vehicle.yaw_inertia=3480"}, sinusoid));
  suv(b.add("suv-inertia-straight-2m", "in_list", "inertia", "", "J x0.8", "straight", {"vehicle.yaw_inertia=2320"},
            straight));
  heldOutOn(suv(b.add("suv-cornering_stiffness-pair-bend-straight", "in_list", "cornering_stiffness", "", "k x0.8", "bend",
                      softer, {})),
            "straight", {"simulation.initial.y=-2", "tracker.excitation_amplitude=0.004", "simulation.duration=15"});
  suv(b.none("suv-none-1-sinusoid", "sinusoid", sinusoid));
  suv(b.none("suv-none-2-bend", "bend", {}));
  suv(b.none("suv-none-3-straight-2m-100Hz", "straight", straight, 100.0));
}

void jittered50Hz(GroupBuilder& b) {
  b.group("50 Hz jittered");
  // 50 Hz logs whose stamps are off their sample times by up to +-4 ms (uniform): a bus's stamps.
  auto jitter = [](BenchmarkCase& c) -> BenchmarkCase& {
    c.stamp_jitter = 0.004;
    return c;
  };
  jitter(b.add("jitter50-cornering_stiffness-sinusoid", "in_list", "cornering_stiffness", "", "k x0.75", "sinusoid",
               {"tire.front.lateral_stiffness=1.5e6", "tire.rear.lateral_stiffness=1.5e6"}, {}, 50.0));
  jitter(b.add("jitter50-crosswind-bend", "in_list", "lateral_disturbance", "", "450 N", "bend", crosswind(450.0, 0.0), {},
               50.0));
  jitter(b.add("jitter50-sensing_delay-lane_change", "in_list", "sensing_delay", "", "+70 ms", "lane_change",
               {"delays.pose_to_tracker=0.27"}, {}, 50.0));
  jitter(b.add("jitter50-inertia-lane_change", "in_list", "inertia", "", "J x1.4, m x1.12", "lane_change",
               bootLoad(1.4, 1.12, 0.05), {}, 50.0));
  jitter(b.add("jitter50-steering_friction-sinusoid", "in_list", "steering_friction", "", "T_c 4 N m", "sinusoid",
               lugreFriction(4.0, 6.0), {}, 50.0));
  jitter(b.add("jitter50-heading_mount-bend", "in_list", "sensor_offset", "heading", "0.7 deg", "bend",
               {"sensors.pose_bias_psi=" + num(0.7 * M_PI / 180.0)}, {}, 50.0));
  jitter(b.none("jitter50-none-1-sinusoid", "sinusoid", {}, 50.0));
  jitter(b.none("jitter50-none-2-straight-2m", "straight", {"simulation.initial.y=2", "tracker.excitation_amplitude=0.004"},
                50.0));
}

}  // namespace

const std::vector<std::string>& suvCar() {
  // Wheelbase, mass and speed of issue 47; the yaw inertia m a b (2,900 kg m^2), tires scaled with the axle
  // load (cornering stiffness 2 a^2 k = 53 kN/rad per axle against the Table 1 car's 40); gains whose closed
  // loop is stable with margin at 25 m/s (lk_stability roots: rightmost oscillatory roots -0.54 +- 0.17 Hz
  // and -0.96 +- 0.50 Hz; k_psi 0.8, k_y 0.05 leave -0.01 at 0.57 Hz, and diverge from 2 m in lk_simulate)
  // and a stronger actuator for the heavier axle (critical tau2 3.2 ms).
  static const std::vector<std::string> car{
      "vehicle.wheelbase=2.65",         "vehicle.cg_to_rear_axle=1.35",       "vehicle.mass=1700",
      "vehicle.yaw_inertia=2900",       "vehicle.steering_mass=14",           "vehicle.steering_inertia=0.35",
      "vehicle.speed=25",               "tire.front.contact_half_length=0.11", "tire.rear.contact_half_length=0.11",
      "tire.front.lateral_stiffness=2.2e6", "tire.rear.lateral_stiffness=2.2e6", "tracker.k_psi=0.4",
      "tracker.k_y=0.015",              "actuator.p=1500"};
  return car;
}

const std::vector<std::string>& independentGroupNames() {
  static const std::vector<std::string> names{"sensor errors", "two at once", "start of a log", "delays near the margin",
                                              "onsets", "varying speed", "another car", "50 Hz jittered"};
  return names;
}

std::vector<BenchmarkCase> independentGroupCases() {
  std::vector<BenchmarkCase> cases;
  GroupBuilder b(cases);
  sensorErrors(b);
  twoAtOnce(b);
  startOfLog(b);
  delaysNearTheMargin(b);
  onsets(b);
  varyingSpeed(b);
  anotherCar(b);
  jittered50Hz(b);
  return cases;
}

}  // namespace lane_keeping
