// The gyro, the heading and the lateral accelerometer laid over each other (heading_agreement.h).
#include "lane_keeping/gap/log/heading_agreement.h"

#include <algorithm>
#include <cmath>

#include "lane_keeping/common/effective_samples.h"
#include "lane_keeping/common/printf_string.h"
#include "lane_keeping/gap/log/angle_unwrap.h"
#include "lane_keeping/gap/log/time_holes.h"

namespace lane_keeping {
namespace {

constexpr double kMinSpeed = 5.0;        ///< [m/s] below it ay / V is the accelerometer's noise over a small V
constexpr double kMinTurned = 0.1;       ///< [rad] a reference turning less shows no scale
constexpr std::size_t kMinSamples = 20;
constexpr double kDegrees = 180.0 / M_PI;

/// [first, last) rows of the stretches: the log's between its holes (time_holes.h), and, where `speed` matters,
/// split where V < kMinSpeed.
std::vector<std::pair<std::size_t, std::size_t>> stretches(const GapLog& log, bool speed) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (const auto& [begin, end] : holeFreeStretches(log.t)) {
    std::size_t first = begin;
    for (std::size_t i = begin; i <= end; ++i) {
      if (i < end && (!speed || std::fabs(log.v[i]) >= kMinSpeed)) continue;
      if (i > first + 1) out.emplace_back(first, i);
      first = i + 1;
    }
  }
  return out;
}

/// The heading a rate channel integrates to (trapezoids), restarting at 0 on each stretch.
std::vector<double> integrated(const GapLog& log, const std::vector<std::pair<std::size_t, std::size_t>>& parts,
                               const std::vector<double>& rate) {
  std::vector<double> out(log.size(), std::numeric_limits<double>::quiet_NaN());
  for (const auto& [a, b] : parts) {
    out[a] = 0.0;
    for (std::size_t i = a + 1; i < b; ++i) out[i] = out[i - 1] + 0.5 * (rate[i] + rate[i - 1]) * (log.t[i] - log.t[i - 1]);
  }
  return out;
}

/// psi without 2 pi jumps: a log read from a file is unwrapped already (gap_log.h); one built in memory may not be.
std::vector<double> unwrapped(std::vector<double> psi) {
  unwrapAngle(&psi);
  return psi;
}

HeadingComparison compare(const GapLog& log, const std::vector<std::pair<std::size_t, std::size_t>>& parts,
                          const std::string& of, const std::vector<double>& y, const std::string& against,
                          const std::vector<double>& x) {
  HeadingComparison c;
  c.of = of;
  c.against = against;
  // Centred per stretch (its constant c_k out), then the normal equations of [scale, drift].
  std::vector<double> xc, yc, tc;
  std::vector<std::size_t> starts;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& [a, b] : parts) {
    double mx = 0.0, my = 0.0, mt = 0.0;
    const double n = static_cast<double>(b - a);
    for (std::size_t i = a; i < b; ++i) mx += x[i] / n, my += y[i] / n, mt += log.t[i] / n;
    starts.push_back(xc.size());
    for (std::size_t i = a; i < b; ++i) {
      xc.push_back(x[i] - mx);
      yc.push_back(y[i] - my);
      tc.push_back(log.t[i] - mt);
      lo = std::min(lo, x[i] - mx);
      hi = std::max(hi, x[i] - mx);
    }
  }
  const std::size_t n = xc.size();
  c.samples = n;
  c.turned = n > 0 ? hi - lo : 0.0;
  if (n < kMinSamples) return c;
  // A reference that turns too little shows no scale; the drift is still there to see (a gyro's bias on a
  // straight road): fitted with the scale held at 1.
  const bool scaled = c.turned >= kMinTurned;
  double sxx = 0.0, sxt = 0.0, stt = 0.0, sxy = 0.0, sty = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double y = scaled ? yc[i] : yc[i] - xc[i];
    sxx += xc[i] * xc[i], sxt += xc[i] * tc[i], stt += tc[i] * tc[i];
    sxy += xc[i] * y, sty += tc[i] * y;
  }
  const double det = scaled ? sxx * stt - sxt * sxt : stt;
  if (!(det > 0.0)) return c;
  const double scale = scaled ? (stt * sxy - sxt * sty) / det : 1.0;
  c.drift = scaled ? (sxx * sty - sxt * sxy) / det : sty / stt;
  // The residual's scatter, counted with its effective sample count within the stretches.
  std::vector<double> e(n);
  double see = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    e[i] = yc[i] - scale * xc[i] - c.drift * tc[i];
    see += e[i] * e[i];
  }
  c.effective_samples = effectiveSampleCount(e, starts);
  const double parameters = scaled ? 2.0 : 1.0;
  const double dof = static_cast<double>(n) - parameters - static_cast<double>(parts.size());
  const double s2 = see / std::max(1.0, dof) * (static_cast<double>(n) / c.effective_samples);
  c.drift_sigma = std::sqrt(s2 * (scaled ? sxx : 1.0) / det);
  if (scaled) {
    c.scale = scale;
    c.scale_sigma = std::sqrt(s2 * stt / det);
  }
  return c;
}

const HeadingComparison* find(const std::vector<HeadingComparison>& all, const std::string& of, const std::string& against) {
  for (const auto& c : all) {
    if (c.of == of && c.against == against && (std::isfinite(c.scale) || std::isfinite(c.drift))) return &c;
  }
  return nullptr;
}

std::string label(const std::string& channel, bool course) {
  if (channel == "yaw_rate") return "the integrated yaw rate";
  if (channel == "psi") return course ? "the course (psi)" : "the heading (psi)";
  return "the integrated ay / V";
}

std::string describe(const HeadingComparison& c, bool course) {
  return label(c.of, course) + printfString(" turns %.3f +- %.3f times ", c.scale, c.scale_sigma) + label(c.against, course) +
         printfString(" (over %.0f deg)", c.turned * kDegrees);
}

/// The references' own systematic error on a scale, beside its standard error: 2 % (gravity's share in a rolled
/// accelerometer's ay, 1-2 % at 1.5 g; a course's and a heading's sources), and where the comparison holds a
/// course (ay / V integrates to one; psi may be one) the body slip inside it, up to kSlip radians over the
/// reference's turn: on a generated correction of a 2 m offset (7 degrees of heading) ay / V turned 0.9 times the
/// heading by the body slip alone, over the race car's 169 degree hairpin the slip is a fraction of a per cent.
constexpr double kReferenceError = 0.02;
constexpr double kSlip = 0.02;  ///< [rad]

double logSigma(const HeadingComparison& c) {
  const double relative = c.scale_sigma / c.scale;
  const double slip = c.holds_course ? kSlip / std::max(c.turned, 1e-9) : 0.0;
  return std::sqrt(relative * relative + kReferenceError * kReferenceError + slip * slip);
}

struct SingleSensorGain {
  std::string sensor;  ///< "yaw_rate", "psi", "ay"; empty where none explains the comparisons
  std::string or_else; ///< the next best where the comparisons cannot tell the two apart (chi-square within 4)
  double gain = 1.0, sigma = 0.0;
  double other_gain = 1.0;
  /// The gyro, fitting best, decided over psi within the Delta chi-square of 4 because psi is an angle (below).
  bool by_angle = false;
};

/// The one sensor whose gain, the other two right, explains the three comparisons: each hypothesis's gain by
/// weighted least squares on log scales (gp = g / p, ga = g / a, pa = p / a), the best by its chi-square. A
/// finding needs the best to leave the comparisons within 3 sigma (chi-square <= 9), its gain off 1 by more than
/// 3 sigma and kScaleTolerance, and all three right (no gain) to fit worse by 9 (3 sigma). Where the next best
/// hypothesis fits within 4 of it (2 sigma), both are named: on a turn of a few degrees ay / V, holding the body
/// slip, cannot tell a gyro's gain from a heading's.
SingleSensorGain oddOneOut(const HeadingComparison& gp, const HeadingComparison& ga, const HeadingComparison& pa) {
  const double r[3] = {std::log(gp.scale), std::log(ga.scale), std::log(pa.scale)};
  const double w[3] = {1.0 / std::pow(logSigma(gp), 2), 1.0 / std::pow(logSigma(ga), 2), 1.0 / std::pow(logSigma(pa), 2)};
  // How each comparison moves with log gain of each sensor: d(log gp, log ga, log pa) / d(log g | log p | log a).
  const struct {
    const char* sensor;
    double d[3];
  } hypotheses[3] = {{"yaw_rate", {1, 1, 0}}, {"psi", {-1, 0, 1}}, {"ay", {0, -1, -1}}};
  double none = 0.0;
  for (int i = 0; i < 3; ++i) none += w[i] * r[i] * r[i];
  struct Fitted {
    const char* sensor;
    double chi2, x, sx;
  };
  std::vector<Fitted> fitted;
  for (const auto& h : hypotheses) {
    double num = 0.0, den = 0.0;
    for (int i = 0; i < 3; ++i) num += w[i] * h.d[i] * r[i], den += w[i] * h.d[i] * h.d[i];
    const double x = num / den;
    double chi2 = 0.0;
    for (int i = 0; i < 3; ++i) chi2 += w[i] * std::pow(r[i] - h.d[i] * x, 2);
    fitted.push_back({h.sensor, chi2, x, 1.0 / std::sqrt(den)});
  }
  std::sort(fitted.begin(), fitted.end(), [](const Fitted& a, const Fitted& b) { return a.chi2 < b.chi2; });
  const Fitted& top = fitted[0];
  const bool off = std::fabs(top.x) > std::max(3.0 * top.sx, std::log1p(kScaleTolerance));
  SingleSensorGain best;
  if (top.chi2 <= 9.0 && off && none - top.chi2 >= 9.0) {
    best.sensor = top.sensor;
    best.gain = std::exp(top.x);
    best.sigma = best.gain * top.sx;
    if (fitted[1].chi2 - top.chi2 < 4.0) {
      best.other_gain = std::exp(fitted[1].x);
      // A heading or a course is an angle, measured absolutely (a GNSS course, a magnetometer, a map match): it has
      // no gain to be off by several per cent short of a unit, which the units check finds (57.3). A gyro's gain is
      // a calibration that is off: where the gyro fits best and psi's gain is the only look-alike, the gyro is it.
      // (Not the other way round: where psi's gain fits best, the data and this reasoning disagree: undecided.)
      if (std::string(top.sensor) == "yaw_rate" && std::string(fitted[1].sensor) == "psi") {
        best.by_angle = true;
      } else {
        best.or_else = fitted[1].sensor;
      }
    }
  }
  return best;
}

}  // namespace

bool HeadingComparison::scaleOff() const {
  return std::isfinite(scale) && std::fabs(std::log(scale)) > std::max(3.0 * logSigma(*this), std::log1p(kScaleTolerance));
}

bool HeadingComparison::drifts() const {
  return std::isfinite(drift) && std::fabs(drift) > std::max(3.0 * drift_sigma, kDriftTolerance);
}

std::vector<HeadingComparison> headingComparisons(const GapLog& log) {
  std::vector<HeadingComparison> out;
  if (log.size() < kMinSamples) return out;
  const bool gyro = log.has("yaw_rate", true), heading = log.has("psi", true);
  const bool accelerometer = log.has("ay", true) && log.hasSpeed();
  const auto all = stretches(log, false);
  if (gyro && heading) {
    out.push_back(compare(log, all, "yaw_rate", integrated(log, all, log.yaw_rate), "psi", unwrapped(log.psi)));
    out.back().holds_course = log.psi_is_course;
  }
  if (accelerometer && (gyro || heading)) {
    const auto moving = stretches(log, true);
    std::vector<double> course_rate(log.size(), 0.0);
    for (std::size_t i = 0; i < log.size(); ++i) course_rate[i] = log.ay[i] / std::max(kMinSpeed, std::fabs(log.v[i]));
    const std::vector<double> from_ay = integrated(log, moving, course_rate);
    if (gyro) out.push_back(compare(log, moving, "yaw_rate", integrated(log, moving, log.yaw_rate), "ay", from_ay));
    if (heading) out.push_back(compare(log, moving, "psi", unwrapped(log.psi), "ay", from_ay));
    for (HeadingComparison& c : out) c.holds_course = c.holds_course || c.against == "ay";
  }
  return out;
}

std::vector<InputCheck> headingAgreementChecks(const GapLog& log) {
  std::vector<InputCheck> out;
  const std::vector<HeadingComparison> all = headingComparisons(log);
  const bool course = log.psi_is_course;
  auto add = [&](const std::string& channel, const std::string& kind, const std::string& detail) {
    out.push_back(inputCheck(log.source, channel, kind, detail));
  };
  const HeadingComparison* gp = find(all, "yaw_rate", "psi");
  const HeadingComparison* ga = find(all, "yaw_rate", "ay");
  const HeadingComparison* pa = find(all, "psi", "ay");
  const std::string reported = "; reported, not corrected (the diagnosis reads the log as it is: a log mapping's scale "
                               "corrects it)";
  auto scaled = [](const HeadingComparison* c) { return c != nullptr && std::isfinite(c->scale); };
  if (!scaled(gp)) gp = nullptr;
  if (!scaled(ga)) ga = nullptr;
  if (!scaled(pa)) pa = nullptr;
  const HeadingComparison* drift = find(all, "yaw_rate", "psi");
  if (gp && ga && pa) {
    // Three sensors, three comparisons of their gains g, p, a: gp = g / p, ga = g / a, pa = p / a. Which one
    // sensor's gain, the other two right, explains all three (least squares on the logs of the scales, each
    // comparison weighed by its standard error and the references' own systematic error)?
    const SingleSensorGain best = oddOneOut(*gp, *ga, *pa);
    if (!best.sensor.empty() && !best.or_else.empty()) {
      add(best.sensor, "scale",
          describe(*gp, course) + ", " + describe(*ga, course) + ", " + describe(*pa, course) +
              ": one sensor's gain is off, " + best.sensor + printfString(" (%.3f)", best.gain) + " or " + best.or_else +
              printfString(" (%.3f)", best.other_gain) +
              "; the comparisons with ay / V, which hold the body slip, cannot tell which over this turn" + reported);
    } else if (best.sensor.empty()) {
      if (gp->scaleOff() || ga->scaleOff() || pa->scaleOff()) {
        add("yaw_rate", "scale",
            "the three turn sensors disagree and no one sensor's gain explains it: " + describe(*gp, course) + ", " +
                describe(*ga, course) + ", " + describe(*pa, course) + reported);
      }
    } else if (best.sensor == "yaw_rate" && best.by_angle) {
      add("yaw_rate", "scale",
          describe(*gp, course) + ", " + describe(*ga, course) + ", " + describe(*pa, course) +
              printfString(": one sensor's gain is off, the gyro's (%.3f) or psi's (%.3f), and the comparisons with ay / V, "
                     "which hold the body slip, cannot tell which over this turn; psi is an angle, with no gain to be "
                     "off short of a unit: the gyro reads %.3f +- %.3f of the yaw rate",
                     best.gain, best.other_gain, best.gain, best.sigma) +
              reported);
    } else if (best.sensor == "yaw_rate") {
      add("yaw_rate", "scale",
          describe(*gp, course) + " and " + printfString("%.3f +- %.3f times", ga->scale, ga->scale_sigma) +
              " the integrated ay / V, while psi and ay / V agree (" + printfString("%.3f", pa->scale) +
              printfString("): the gyro reads %.3f +- %.3f of the yaw rate (a gain error, or an axis tilted by %.0f deg from "
                     "the vertical, which reads its cosine)",
                     best.gain, best.sigma, std::acos(std::clamp(best.gain, 0.0, 1.0)) * kDegrees) +
              reported);
    } else if (best.sensor == "ay") {
      add("ay", "scale",
          "the integrated ay / V turns " + printfString("%.3f", 1.0 / ga->scale) + " times the integrated yaw rate and " +
              printfString("%.3f", 1.0 / pa->scale) + " times " + label("psi", course) +
              printfString(", while the gyro and psi agree (%.3f): the lateral accelerometer reads %.3f +- %.3f of the "
                     "lateral acceleration",
                     gp->scale, best.gain, best.sigma) +
              reported);
    } else {
      add("psi", "scale",
          describe(*pa, course) + printfString(" and the integrated yaw rate %.3f times it, while the gyro and ay / V agree "
                                         "(%.3f): psi turns %.3f +- %.3f of the car's turning (its unit or its source)",
                                         1.0 / gp->scale, ga->scale, best.gain, best.sigma) +
              reported);
    }
  } else {
    // Two sensors: which of them is off cannot be told.
    for (const HeadingComparison* c : {gp, ga, pa}) {
      if (c == nullptr || !c->scaleOff()) continue;
      add(c->of, "scale",
          describe(*c, course) + ": one of the two reads a scale off (no third channel here tells which)" + reported);
    }
  }
  if (drift != nullptr && drift->drifts()) {
    const HeadingComparison* gp = drift;
    // The gyro and psi drift apart: ay / V, where it tells, sides with one of them.
    const HeadingComparison* gd = find(all, "yaw_rate", "ay");
    const bool told = gd != nullptr && std::isfinite(gd->drift);
    const bool psi_drifts =
        told && std::fabs(gd->drift - gp->drift) > 3.0 * std::hypot(gd->drift_sigma, gp->drift_sigma) + kDriftTolerance;
    if (psi_drifts) {
      add("psi", "bias",
          printfString("psi drifts %.4f +- %.4f rad/s from the integrated yaw rate, which ay / V follows (the gyro drifts "
                 "%.4f +- %.4f rad/s from it): psi's source drifts (an inertial heading's), not the gyro; reported, "
                 "not corrected",
                 -gp->drift, gp->drift_sigma, gd->drift, gd->drift_sigma));
    } else {
      add("yaw_rate", "bias",
          printfString("the yaw rate drifts %.4f +- %.4f rad/s from psi's rate (%.3f deg/s over %.0f s)", gp->drift,
                 gp->drift_sigma, gp->drift * kDegrees, log.duration()) +
              (told ? printfString(" and %.4f +- %.4f rad/s from ay / V: a gyro bias", gd->drift, gd->drift_sigma)
                    : std::string(": a gyro bias, or psi's source drifting (no ay / V here to tell which)")) +
              (course ? " (psi is a course: a body slip that grows over the log would drift it too)" : std::string()) +
              "; corrected before the fits where decided (--no-measured-corrections: reported only)");
    }
  }
  return out;
}

namespace {

/// The gyro's gain as one log decides it (the three-way comparison naming the gyro alone), or NaN.
std::pair<double, double> decidedGyroScale(const std::vector<HeadingComparison>& all) {
  const HeadingComparison* gp = find(all, "yaw_rate", "psi");
  const HeadingComparison* ga = find(all, "yaw_rate", "ay");
  const HeadingComparison* pa = find(all, "psi", "ay");
  if (gp && ga && pa && std::isfinite(gp->scale) && std::isfinite(ga->scale) && std::isfinite(pa->scale)) {
    const SingleSensorGain best = oddOneOut(*gp, *ga, *pa);
    if (best.sensor == "yaw_rate" && best.or_else.empty()) return {best.gain, best.sigma};
  }
  return {NAN, NAN};
}

/// The gyro's drift from psi as one log decides it (ay / V, where it tells, drifting alike), or NaN.
std::pair<double, double> decidedGyroDrift(const std::vector<HeadingComparison>& all) {
  const HeadingComparison* gp = find(all, "yaw_rate", "psi");
  const HeadingComparison* ga = find(all, "yaw_rate", "ay");
  if (gp == nullptr || !gp->drifts()) return {NAN, NAN};
  if (ga != nullptr && std::isfinite(ga->drift) &&
      std::fabs(ga->drift - gp->drift) > 3.0 * std::hypot(ga->drift_sigma, gp->drift_sigma) + kDriftTolerance) {
    return {NAN, NAN};  // the gyro agrees with ay / V: psi is what drifts
  }
  return {gp->drift, gp->drift_sigma};
}

}  // namespace

std::vector<MeasuredSensorError> measuredSensorErrors(const std::vector<const GapLog*>& logs) {
  std::vector<MeasuredSensorError> out;
  struct Kind {
    const char *effect, *parameter, *key;
    double tolerance;
    std::pair<double, double> (*decided)(const std::vector<HeadingComparison>&);
    double (*informative)(const HeadingComparison&, double* sigma);
  };
  const Kind kinds[2] = {
      {"sensor_scale", "scale", "sensors.yaw_rate_scale", kScaleTolerance, decidedGyroScale,
       [](const HeadingComparison& c, double* sigma) {
         *sigma = c.scale * logSigma(c);
         return c.scale;
       }},
      {"sensor_offset", "bias", "sensors.yaw_rate_bias", kDriftTolerance, decidedGyroDrift,
       [](const HeadingComparison& c, double* sigma) {
         *sigma = c.drift_sigma;
         return c.drift;
       }}};
  for (const Kind& kind : kinds) {
    double sum = 0.0, weight = 0.0;
    std::size_t deciding = 0;
    std::string detail;
    std::vector<std::vector<HeadingComparison>> per_log;
    for (const GapLog* log : logs) {
      per_log.push_back(headingComparisons(*log));
      const auto [value, sigma] = kind.decided(per_log.back());
      if (!std::isfinite(value) || !(sigma > 0.0)) continue;
      ++deciding;
      sum += value / (sigma * sigma);
      weight += 1.0 / (sigma * sigma);
      if (detail.empty()) {
        for (const InputCheck& c : headingAgreementChecks(*log)) {
          // (Without "reported, not corrected": this is what is corrected where the diagnosis is asked to.)
          if (c.channel == "yaw_rate" && c.kind == kind.parameter) {
            detail = log->source + ": " + c.detail.substr(0, c.detail.find("; reported, not corrected"));
          }
        }
      }
    }
    if (deciding == 0) continue;
    const double mean = sum / weight;
    // A log whose own comparison with psi tells otherwise contradicts it: nothing is corrected.
    bool contradicted = false;
    for (const auto& all : per_log) {
      const HeadingComparison* gp = find(all, "yaw_rate", "psi");
      if (gp == nullptr) continue;
      double sigma = 0.0;
      const double value = kind.informative(*gp, &sigma);
      if (std::isfinite(value) && std::fabs(value - mean) > std::max(3.0 * sigma, kind.tolerance)) contradicted = true;
    }
    if (contradicted) continue;
    MeasuredSensorError e;
    e.effect = kind.effect;
    e.form = "yaw_rate";
    e.parameter = kind.parameter;
    e.key = kind.key;
    e.value = mean;
    e.sigma = 1.0 / std::sqrt(weight);
    e.logs = deciding;
    e.detail = detail;
    out.push_back(e);
  }
  return out;
}

}  // namespace lane_keeping
