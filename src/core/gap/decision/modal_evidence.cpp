#include "lane_keeping/gap/decision/modal_evidence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>

#include "lane_keeping/analysis/critical_delay.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "lane_keeping/common/parallel_for.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// Rightmost roots refined: a lightly damped mode lies among them (its real part is small), the fast mode
/// at +1.5 ms is the 1st of 4 above 20 Hz and the 5th root from the right.
constexpr int kSeeds = 24;

std::string number(const char* format, double x) {
  char text[48];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

/// The best mode over a scan of parameter j of `fit` (the others at their fits); modal = its value.
struct ScanResult {
  bool found = false;
  double value = 0.0;
  RingingMode mode;
};

/// Whether `config`'s loop, linearised about straight driving, is stable (false where it cannot be linearised).
bool linearlyStable(const SimConfig& config) {
  try {
    SpectrumOptions options;
    options.seeds = kSeeds;
    return computeSpectrum(loopDelaySystem(config), options).abscissa() < 0.0;
  } catch (const std::exception&) {
    return false;
  }
}

/// `fit` with parameter j at `value`, applied to the nominal.
SimConfig withParameter(const CandidateFit& fit, const SimConfig& nominal, std::size_t j, double value) {
  SimConfig config = nominal;
  std::vector<double> at = fit.theta;
  at[j] = value;
  fit.effect->apply(at, config);
  return config;
}

/// Where parameter j's fit lies beyond the loop's margin (its linearised loop unstable) and its lower bound
/// does not: the margin along j between them, by bisection to within a hundredth of a standard error; NaN
/// otherwise (a fit within the margin, or a parameter whose whole range below the fit is unstable).
double marginBelow(const CandidateFit& fit, const SimConfig& nominal, std::size_t j, double sigma) {
  const EffectParameter& p = fit.effect->params[j];
  double unstable = fit.theta[j], stable = p.lower;
  if (linearlyStable(withParameter(fit, nominal, j, unstable)) || !linearlyStable(withParameter(fit, nominal, j, stable))) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  for (int k = 0; k < 40 && unstable - stable > 0.01 * sigma; ++k) {
    const double mid = 0.5 * (stable + unstable);
    (linearlyStable(withParameter(fit, nominal, j, mid)) ? stable : unstable) = mid;
  }
  return stable;
}

ScanResult scanParameter(const CandidateFit& fit, const SimConfig& nominal, std::size_t j, const LoopRinging& ringing,
                         int threads) {
  const EffectParameter& p = fit.effect->params[j];
  const double theta = fit.theta[j];
  const double sigma = j < fit.sigma.size() ? fit.sigma[j] : std::numeric_limits<double>::quiet_NaN();
  double lo = theta, hi = theta;
  if (std::isfinite(sigma) && sigma > 0.0) {
    lo = std::max(p.lower, theta - kModalSigmas * sigma);
    hi = std::min(p.upper, theta + kModalSigmas * sigma);
    // A fit beyond the margin by more than the scan reaches: a bounded log is a stable loop, so the truth lies
    // below the margin, and the replays' optimum beyond it is the noise's pull. The scan then covers the
    // 2 kModalSigmas standard errors below the margin (a fresh noise draw of the independent family's +1.7 ms
    // log fitted 1.863 +- 0.023 ms, the margin at about 1.75 ms: its +-3 sigma held no stable value).
    const double margin = marginBelow(fit, nominal, j, sigma);
    if (std::isfinite(margin) && margin < lo) {
      hi = margin;
      lo = std::max(p.lower, margin - 2.0 * kModalSigmas * sigma);
    }
  }
  const int points = hi > lo ? kModalScanPoints : 1;
  std::vector<double> values(points);
  for (int k = 0; k < points; ++k) values[k] = points == 1 ? theta : lo + (hi - lo) * k / (points - 1);
  std::vector<ScanResult> found(points);
  parallelFor(values.size(), threads, [&](std::size_t k) {
    found[k].value = values[k];
    found[k].found = ringingMode(withParameter(fit, nominal, j, values[k]), ringing, &found[k].mode);
  });
  ScanResult best;
  for (const ScanResult& r : found) {
    if (!r.found) continue;
    // Nearest the ringing in alias; between equally near, nearest the replay fit.
    if (!best.found || r.mode.error < best.mode.error - 1e-9 ||
        (std::abs(r.mode.error - best.mode.error) <= 1e-9 && std::abs(r.value - theta) < std::abs(best.value - theta))) {
      best = r;
    }
  }
  return best;
}

}  // namespace

double aliasedFrequency(double frequency, double rate) {
  double a = std::fmod(std::abs(frequency), rate);
  return a > 0.5 * rate ? rate - a : a;
}

bool ringingMode(const SimConfig& config, const LoopRinging& ringing, RingingMode* mode) {
  Spectrum spectrum;
  try {
    SpectrumOptions options;
    options.seeds = kSeeds;
    spectrum = computeSpectrum(loopDelaySystem(config), options);
  } catch (const std::exception&) {
    return false;  // a configuration the linearisation does not take (a tire model it has no slope for)
  }
  if (!(spectrum.abscissa() < 0.0)) return false;
  const double tolerance = ringing.bin_width > 0.0 ? ringing.bin_width : 0.02 * ringing.rate;
  bool found = false;
  for (const CharacteristicRoot& root : spectrum.roots) {
    const double f = root.frequencyHz();
    const double decay = -root.value.real();
    if (!root.refined || !(f > 0.0) || decay > f / kModalCycles) continue;
    const double alias = aliasedFrequency(f, ringing.rate);
    const double error = std::abs(alias - ringing.frequency);
    if (error > tolerance || (found && error >= mode->error)) continue;
    *mode = RingingMode{f, decay, alias, error};
    found = true;
  }
  return found;
}

std::vector<ModalSupport> modalSupport(const std::vector<CandidateFit>& fits, const SimConfig& nominal,
                                       const std::vector<LoopRinging>& ringings, const std::string& subsystem,
                                       double min_shrink, int threads, std::vector<std::string>* notes) {
  std::vector<ModalSupport> out;
  for (const LoopRinging& ringing : ringings) {
    RingingMode nominal_mode;
    if (ringingMode(nominal, ringing, &nominal_mode)) {
      notes->push_back("modal evidence: the nominal loop has a lightly damped mode at " +
                       number("%.1f", nominal_mode.frequency) + " Hz (decay " + number("%.3g", nominal_mode.decay) +
                       " 1/s) that " + ringing.source + "'s " + ringing.column + " ringing at " +
                       number("%.1f", ringing.frequency) + " Hz may be: no candidate is scored on it");
      continue;
    }
    std::vector<std::string> matched;
    for (const CandidateFit& fit : fits) {
      // A fit whose least-squares closed loop leaves the logged bounds is scanned too: near the margin the
      // replays' optimum may lie beyond it (the p = 1500 log's 2.30 ms for 2.2), and the scan keeps only
      // values whose linearised loop is stable.
      if (!fit.ok || !fit.effect->changes(subsystem)) continue;
      if (!(fit.train_before > 0.0) || 1.0 - fit.train_after / fit.train_before < min_shrink) continue;
      ModalSupport best;
      bool found = false;
      for (std::size_t j = 0; j < fit.theta.size() && j < fit.effect->params.size(); ++j) {
        const ScanResult r = scanParameter(fit, nominal, j, ringing, threads);
        if (!r.found || (found && r.mode.error >= best.mode.error)) continue;
        found = true;
        best.effect = fit.effect->name;
        best.form = fit.effect->form;
        best.parameter = fit.effect->params[j].name;
        best.index = j;
        best.fitted = fit.theta[j];
        best.sigma = j < fit.sigma.size() ? fit.sigma[j] : std::numeric_limits<double>::quiet_NaN();
        best.modal = r.value;
        best.mode = r.mode;
        best.ringing = ringing;
      }
      if (!found) continue;
      matched.push_back(best.label());
      const auto same = std::find_if(out.begin(), out.end(), [&](const ModalSupport& s) { return s.label() == best.label(); });
      if (same == out.end()) {
        out.push_back(best);
      } else if (best.mode.error < same->mode.error) {
        *same = best;
      }
    }
    std::string list;
    for (const auto& m : matched) list += (list.empty() ? "" : ", ") + m;
    notes->push_back("modal evidence: " + ringing.source + "'s " + ringing.column + " ringing at " +
                     number("%.1f", ringing.frequency) + " Hz is a lightly damped mode of the loop under " +
                     (list.empty() ? std::string("no candidate") : list) + " (the nominal's roots hold none there)");
  }
  return out;
}

CandidateFit atModalValue(const CandidateFit& fit, const ModalSupport& support, const SimConfig& nominal) {
  CandidateFit out = fit;
  if (support.index < out.theta.size()) out.theta[support.index] = support.modal;
  out.corrected = nominal;
  fit.effect->apply(out.theta, out.corrected);
  const CandidateEffect* effect = fit.effect;
  const std::vector<double> theta = out.theta;
  out.change = [effect, theta](SimConfig& c) { effect->apply(theta, c); };
  out.unbounded_on.clear();  // its linearised loop is stable (ringingMode); the closed loop is not re-checked
  return out;
}

std::string modalReason(const ModalSupport& s) {
  return s.label() + " with " + s.parameter + " = " + number("%.4g", s.modal) + " (its replay fit " +
         number("%.4g", s.fitted) + " +- " + number("%.2g", s.sigma) + ") gives the loop a mode at " +
         number("%.1f", s.mode.frequency) + " Hz decaying at " + number("%.3g", s.mode.decay) + " 1/s (" +
         number("%.0f", s.mode.frequency / std::max(s.mode.decay, 1e-9)) +
         " cycles to 1/e), which a log at " + number("%.0f", s.ringing.rate) + " Hz sees at " +
         number("%.1f", s.mode.alias) + " Hz: the logged " + (s.ringing.column == "delta" ? "steering angle" : "steering torque") +
         " rings at " + number("%.1f", s.ringing.frequency) + " Hz, which the nominal loop's roots do not";
}

}  // namespace diagnosis
}  // namespace lane_keeping
