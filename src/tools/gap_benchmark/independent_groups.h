#pragma once
/// The groups of the independent benchmark family that issues 46 (item 7) and 47 ask for, each scored in
/// its own table (BenchmarkCase::group; docs/gap.md, "The independent family's groups"):
///
///   sensor errors           a yaw-rate, steering-angle and lateral-acceleration offset, a heading mount, a
///                           yaw-rate and a steering-angle latency, a gyro scale and a steering ratio, each
///                           on two manoeuvres (once with white noise, once through a vehicle bus's
///                           quantised, held or coloured channels); no-effect logs through such buses; three
///                           sensor errors together with a physical effect
///   two at once             two physical effects in one car, a training and a held-out run on other roads
///   start of a log          effects that live in the first seconds (a 2 m correction that saturates a
///                           48 N m torque limit, a large transient on a slippery road, ...)
///   delays near the margin  actuation delays that bring the steering loop near its critical delay
///   onsets                  effects that set in mid-run (runtime changes of the truth), single log and pairs
///   varying speed           in-list effects on runs whose speed varies along the road
///   another car             an SUV-like car with its own gains: a stiffness loss, an inertia change, none
///   50 Hz jittered          50 Hz logs whose stamps jitter
///
/// Seeds from 20001 on: none of these logs is one anything was tuned on.
#include <string>
#include <vector>

#include "gap_benchmark/benchmark_cases.h"

namespace lane_keeping {

/// The group names, in the order the scorer prints their tables.
const std::vector<std::string>& independentGroupNames();

/// The cases of the groups above (independentCases() appends them to the family's first cases).
std::vector<BenchmarkCase> independentGroupCases();

/// The SUV-like car of "another car" (key=value, BenchmarkCase::car): 2.65 m wheelbase, 1,700 kg,
/// 25 m/s, its tires and its own stable gains.
const std::vector<std::string>& suvCar();

}  // namespace lane_keeping
