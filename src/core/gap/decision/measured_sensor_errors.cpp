// Sensor errors measured before any model, against the verdict's effects (measured_sensor_errors.h).
#include "lane_keeping/gap/decision/measured_sensor_errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "lane_keeping/common/brief_number.h"
#include "lane_keeping/gap/fit/candidate_effects.h"

namespace lane_keeping {
namespace diagnosis {

std::vector<std::string> measuredSensorErrorNotes(const GapReport& report) {
  // The schema column an input check names -> the sensor candidates' form for it (docs/gap.md, "Sensor and
  // data errors").
  static const std::map<std::string, std::string> kForm{
      {"yaw_rate", "yaw_rate"}, {"psi", "heading"}, {"ay", "lateral_acceleration"}, {"delta", "steering_angle"}};
  // (Not the steering's `offset` on the straights, straight_line_steering.h: one direction of travel cannot tell
  // it from a crosswind, and on the benchmark's crosswind logs the note would blame the side force it found.)
  static const std::map<std::string, std::string> kEffect{{"scale", "sensor_scale"}, {"bias", "sensor_offset"}};
  std::set<std::string> named;
  for (const VerdictEffect& e : report.verdict.effects) named.insert(e.effect + " (" + e.form + ")");
  if (report.verdict.effects.empty() && !report.verdict.effect.empty()) {
    named.insert(report.verdict.effect + " (" + report.verdict.form + ")");
  }
  std::vector<std::string> out;
  std::set<std::string> said;
  for (const InputCheckEntry& c : report.input_checks) {
    const auto effect = kEffect.find(c.kind);
    const auto form = kForm.find(c.channel);
    if (effect == kEffect.end() || form == kForm.end()) continue;
    if (c.kind == "bias" && c.channel != "yaw_rate") continue;  // a heading's drift is no candidate's (a mount is constant)
    const std::string label = effect->second + " (" + form->second + ")";
    if (named.count(label) || !said.insert(label).second) continue;
    std::size_t logs = 0;
    for (const InputCheckEntry& d : report.input_checks) logs += d.kind == c.kind && d.channel == c.channel;
    // A psi or a_y scale is no candidate's (the sensor candidates scale the yaw rate and the steering angle):
    // the note says so rather than name a label no fit could have.
    const bool candidate = std::any_of(candidateEffects().begin(), candidateEffects().end(),
                                       [&](const CandidateEffect& e) { return e.label() == label; });
    const std::string missing = candidate ? label + " is not among them"
                                          : "no candidate models a " + c.kind + " error of " + c.channel;
    out.push_back("measured before any model: the input checks find a " + c.kind + " error on " + c.channel + " (" +
                  std::to_string(logs) + (logs == 1 ? " log" : " logs") + "; " + c.log + ": " + c.detail +
                  ") that the verdict's effects do not hold (" + missing + "): they may stand in "
                  "for it; correct the log (the log mapping's scale or offset of " + c.channel +
                  ") and diagnose again");
  }
  return out;
}

ConfigChange correctionOf(const std::vector<MeasuredSensorError>& measured) {
  return [measured](SimConfig& c) {
    for (const MeasuredSensorError& e : measured) {
      if (e.key == "sensors.yaw_rate_scale") c.sensors.yaw_rate_scale = e.value;
      if (e.key == "sensors.yaw_rate_bias") c.sensors.yaw_rate_bias = e.value;
    }
  };
}

void withMeasuredErrors(GapReport* report, const std::vector<MeasuredSensorError>& measured, double gap_as_logged,
                        double gap_corrected) {
  GapVerdict& v = report->verdict;
  const bool named = !(v.effect.empty() || v.effect == "unexplained");
  // The diagnosis's own gaps are against the corrected nominal's noise-only reference; carried onto the gap as
  // logged's by the ratio of the two measures of the corrected gap (k), its shares by the corrected gap's part.
  const double k = v.gap_before > 0.0 ? gap_corrected / v.gap_before : 0.0;
  const double part = gap_as_logged > 0.0 ? gap_corrected / gap_as_logged : 0.0;
  const double measured_share = gap_as_logged > 0.0 ? 1.0 - part : 0.0;
  std::vector<VerdictEffect> effects;
  std::string what;
  for (const MeasuredSensorError& m : measured) {
    VerdictEffect e;
    e.effect = m.effect;
    e.form = m.form;
    e.params[m.parameter] = m.value;
    e.param_sigma[m.parameter] = m.sigma;
    e.config[m.key] = briefNumber(m.value);
    e.sensor = true;
    e.measured = true;
    e.evidence = std::numeric_limits<double>::quiet_NaN();  // measured, not fitted: no held-out evidence
    e.share = measured_share / static_cast<double>(measured.size());  // (together; not apportioned finer)
    e.gap_after = gap_corrected;
    effects.push_back(e);
    what += (what.empty() ? "" : "; ") + m.effect + " (" + m.form + ") " + m.parameter + " " + briefNumber(m.value) +
            " +- " + briefNumber(m.sigma) + " (" + std::to_string(m.logs) + (m.logs == 1 ? " log" : " logs") + "; " +
            m.detail + ")";
  }
  for (VerdictEffect e : v.effects) {
    e.share *= part;
    e.gap_after *= k;
    effects.push_back(e);
  }
  const double leader_share = named && !v.effects.empty() ? v.effects.front().share * part : 0.0;
  const std::string before = "measured before any model, and corrected before the diagnosis: " + what +
                             "; the held-out gap as logged " + briefNumber(gap_as_logged) + ", with the correction " +
                             briefNumber(gap_corrected);
  if (!named && !(measured_share > 0.0)) {
    // Nothing explains the gap, and the correction does not shrink it either: the measured errors are facts
    // about the sensors, not the gap's cause (the race car's lap 6: its gyro's 0.829, measured as on its other
    // laps, raises the held-out gap 0.626 -> 0.773). The verdict stays unexplained; the reason and a note say
    // what was measured and corrected.
    v.reason = before + " (the correction does not shrink the gap, so it names no cause of it); with it corrected: " + v.reason;
    v.gap_before = v.gap_after = gap_as_logged;  // nothing named: nothing removed, as in any unexplained verdict
    v.shrink = 0.0;
    report->notes.push_back("measured before any model and corrected before the fits: " + what +
                            "; it does not shrink the held-out gap (as logged " + briefNumber(gap_as_logged) +
                            ", with the correction " + briefNumber(gap_corrected) + "): a sensor fact, not the gap's cause");
    return;
  }
  if (!named || measured_share >= leader_share) {
    // The measured errors lead: the first of them is the verdict's effect.
    std::stable_partition(effects.begin(), effects.end(), [](const VerdictEffect& e) { return e.measured; });
    v.reason = before + (named ? "; on top of it: " : "; with it corrected: ") + v.reason;
    v.effect = effects.front().effect;
    v.form = effects.front().form;
    v.confusable_with.clear();
    v.partial = PartialExplanation{};
    v.confidence = std::clamp(measured_share, 0.0, 1.0);
    v.gap_after = gap_corrected;
    v.basis = "measured";
  } else {
    // A fitted effect removes more: it leads (with the measured errors corrected), they follow it.
    std::stable_partition(effects.begin(), effects.end(), [&](const VerdictEffect& e) {
      return !e.measured && e.effect == v.effect && e.form == v.form;
    });
    v.reason += "; besides, " + before;
    v.gap_after *= k;
  }
  v.gap_before = gap_as_logged;
  v.shrink = gap_as_logged > 0.0 ? 1.0 - v.gap_after / gap_as_logged : 0.0;
  v.combined_gap_after = named ? v.combined_gap_after * k : gap_corrected;
  v.combined_shrink = gap_as_logged > 0.0 ? 1.0 - v.combined_gap_after / gap_as_logged : 0.0;
  v.effects = effects;
  report->notes.push_back("measured before any model and corrected before the fits: " + what +
                          "; where, the ranking and the per-subsystem figures are of the logs so corrected, the verdict's "
                          "gaps and how far's closed loop from the nominal as configured");
}

}  // namespace diagnosis
}  // namespace lane_keeping
