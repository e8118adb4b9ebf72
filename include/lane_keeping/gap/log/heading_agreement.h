#pragma once
/// Three sensors of a car's log measure how it turns: the gyro (yaw_rate), the heading or course (psi) and
/// the lateral accelerometer (ay / V is the rate of the course). What a vehicle-dynamics engineer does with a
/// bus log before any model: integrate the gyro over the corners and lay it over the heading, and over the
/// integral of ay / V. Where two of the three agree and the third does not, the third is the wrong sensor;
/// a gyro that reads 15 % low turns the integrated heading 15 % short of the course, whatever the car's tires
/// (docs/real_logs/super_fj_fuji.md: 0.853 over a 147 degree hairpin). Model-free: no vehicle parameter
/// enters, so a tire or a side force cannot absorb what it finds (the model-based candidates can, and on the
/// race car's laps they did).
///
/// Each comparison fits, over the log's stretches without holes (and, where ay / V is a reference, above
/// 5 m/s),
///   heading_of(t) = scale * heading_against(t) + drift * t + c_k        (c_k: one constant per stretch)
/// by least squares on the stretch-centred series; scale's and drift's standard errors are the residual's
/// scatter through (X^T X)^-1, counted with the effective sample count n (1 - rho1) / (1 + rho1) of the
/// residual (rho1 its lag-1 autocorrelation: the body slip inside a course, or an integrated sensor's noise,
/// is slow, and 20 Hz samples of it are not independent ones).
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/input_checks.h"

namespace lane_keeping {

struct HeadingComparison {
  std::string of;       ///< the heading compared: "yaw_rate" (its integral) or "psi"
  std::string against;  ///< the reference heading: "psi" or "ay" (the integral of ay / V)
  double scale = std::numeric_limits<double>::quiet_NaN();
  double scale_sigma = std::numeric_limits<double>::quiet_NaN();
  double drift = std::numeric_limits<double>::quiet_NaN();        ///< [rad/s] of's rate minus scale * against's
  double drift_sigma = std::numeric_limits<double>::quiet_NaN();  ///< [rad/s]
  double turned = 0.0;         ///< [rad] the reference heading's range over the samples compared
  /// A course is inside the comparison (ay / V integrates to one; psi is one where the log mapping says so): the
  /// body slip lies between it and a heading.
  bool holds_course = false;
  std::size_t samples = 0;
  double effective_samples = 0.0;
  /// The scale differs from 1 by more than kScaleTolerance and by more than 3 times its standard error and the
  /// references' own systematic error (2 %: the body slip inside a course, gravity's share in a rolled
  /// accelerometer) together.
  bool scaleOff() const;
  /// The drift differs from 0 by more than 3 standard errors and more than kDriftTolerance.
  bool drifts() const;
};

/// A gyro's, an accelerometer's or a heading's gain error below this is within a road car's calibration
/// (a few per cent) and not reported.
constexpr double kScaleTolerance = 0.03;
/// [rad/s] a gyro drift below this (0.11 deg/s) is not reported: a MEMS gyro's turn-on bias is of that order,
/// and the model-based candidate `sensor_offset (yaw_rate)` resolves smaller ones.
constexpr double kDriftTolerance = 0.002;

/// The comparisons the log's channels allow: the gyro against psi and against ay / V, psi against ay / V.
/// A pair is left out where a channel is absent or too short (fewer than 20 samples compared); where the
/// reference turns less than 0.1 rad there is no scale to compare (NaN) and the drift is fitted with the scale
/// held at 1 (a gyro's bias shows on a straight road too).
std::vector<HeadingComparison> headingComparisons(const GapLog& log);

/// The findings, as input checks of kind `scale` (where there are three sensors, the one whose gain alone, the
/// other two right, explains the three comparisons; where there are two, both named, undecided) and `bias` (the gyro drifting from psi): each with
/// its numbers, what it means and what the diagnosis does (it reports; it does not correct the log).
std::vector<InputCheck> headingAgreementChecks(const GapLog& log);

/// A sensor error the checks measure and decide on (the gyro's scale where it alone explains the three
/// comparisons; its drift from psi where ay / V does not contradict it), over every log given: what the
/// diagnosis corrects before any model (diagnosis.h, DiagnosisOptions::correct_measured_sensor_errors).
struct MeasuredSensorError {
  std::string effect;     ///< the sensor candidate it is: "sensor_scale" or "sensor_offset"
  std::string form;       ///< its channel's form: "yaw_rate"
  std::string parameter;  ///< "scale" or "bias"
  std::string key;        ///< the configuration key that holds it: "sensors.yaw_rate_scale", "sensors.yaw_rate_bias"
  double value = 0.0, sigma = 0.0;  ///< inverse-variance mean over the logs that decide it, its standard error
  std::size_t logs = 0;             ///< logs that decide it
  std::string detail;               ///< the first deciding log's finding
};

/// The errors decided on at least one log and contradicted by none (a log whose comparison, informative,
/// puts the value more than 3 of its standard errors and kScaleTolerance / kDriftTolerance from the mean).
std::vector<MeasuredSensorError> measuredSensorErrors(const std::vector<const GapLog*>& logs);

}  // namespace lane_keeping
