// The steering loop's ringing a log holds and its nominal loop does not (loop_ringing.h, issue 47 kind 3):
// found at its aliased frequency where the log rings, not where the nominal rings as much or nothing rings.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "lane_keeping/gap/evaluation/loop_ringing.h"

namespace lane_keeping {
namespace {

/// 20 s at 100 Hz: a slow torque and steering angle; `ring` N m of a 129.4 Hz mode (swelling and ebbing
/// by half over 3 s) on the torque; white noise (0.2 N m, 2e-4 rad) unless `noise_free`.
GapLog steeringLog(double ring, bool noise_free, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  GapLog log;
  log.source = "ringing.csv";
  for (int i = 0; i < 2000; ++i) {
    const double t = 0.01 * i;
    log.t.push_back(t);
    const double slow = std::sin(2.0 * M_PI * 0.5 * t);
    log.torque.push_back(20.0 * slow + ring * (1.0 + 0.5 * std::sin(2.0 * M_PI * t / 3.0)) * std::sin(2.0 * M_PI * 129.4 * t) +
                         (noise_free ? 0.0 : 0.2 * unit(rng)));
    log.delta.push_back(0.02 * slow + (noise_free ? 0.0 : 2e-4 * unit(rng)));
  }
  return log;
}

TEST(LoopRinging, FoundAtItsAliasedFrequencyWhereTheNominalDoesNotRing) {
  const LogSignals log(steeringLog(5.0, false));
  const auto ringing = loopRinging(log, steeringLog(0.0, true), LogSignals::kTorque, "torque");
  ASSERT_TRUE(ringing.has_value());
  EXPECT_NEAR(ringing->frequency, 129.4 - 100.0, 100.0 / 64.0);  // 129.4 Hz seen at 29.4 Hz, within a bin
  EXPECT_NEAR(ringing->rate, 100.0, 1e-9);
  EXPECT_GE(ringing->prominence, kRingingProminence);
  EXPECT_LE(ringing->nominal_share, 1e-6);
  const std::string note = ringingNote("ringing.csv", *ringing);
  EXPECT_NE(note.find("ringing.csv: the logged steering torque rings at 29."), std::string::npos) << note;
  EXPECT_NE(note.find("or 129."), std::string::npos) << note;
  // The steering angle does not ring.
  EXPECT_FALSE(loopRinging(log, steeringLog(0.0, true), LogSignals::kDelta, "delta").has_value());
}

TEST(LoopRinging, NotWhereTheNominalRingsAsMuchOrNothingRings) {
  EXPECT_FALSE(loopRinging(LogSignals(steeringLog(5.0, false)), steeringLog(5.0, true), LogSignals::kTorque, "torque"));
  EXPECT_FALSE(loopRinging(LogSignals(steeringLog(0.0, false)), steeringLog(0.0, true), LogSignals::kTorque, "torque"));
  // A ringing just under the noise level is no evidence.
  EXPECT_FALSE(loopRinging(LogSignals(steeringLog(0.05, false)), steeringLog(0.0, true), LogSignals::kTorque, "torque"));
  // A broadband burst the nominal lacks (a torque limit clipping the start correction fills every bin of the
  // band) is no ringing: 1 s of white noise 100 times the sensor's.
  GapLog burst = steeringLog(0.0, false);
  std::mt19937 rng(3);
  std::normal_distribution<double> unit(0.0, 20.0);
  for (int i = 0; i < 100; ++i) burst.torque[i] += unit(rng);
  EXPECT_FALSE(loopRinging(LogSignals(burst), steeringLog(0.0, true), LogSignals::kTorque, "torque"));
  // Without the channel, or too short for the band: nothing.
  GapLog short_log = steeringLog(5.0, false);
  short_log.t.resize(200);
  short_log.torque.resize(200);
  short_log.delta.resize(200);
  EXPECT_FALSE(loopRinging(LogSignals(short_log), steeringLog(0.0, true), LogSignals::kTorque, "torque"));
  GapLog no_torque = steeringLog(5.0, false);
  no_torque.torque.clear();
  EXPECT_FALSE(loopRinging(LogSignals(no_torque), steeringLog(0.0, true), LogSignals::kTorque, "torque"));
}

}  // namespace
}  // namespace lane_keeping
