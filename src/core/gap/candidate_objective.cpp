#include "lane_keeping/gap/candidate_objective.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lane_keeping {
namespace diagnosis {

CandidateObjective::CandidateObjective(const CandidateEffect& effect, const SimConfig& nominal,
                                       const std::vector<Dataset>& data, const ReplayOptions& options,
                                       const Sigma1Cache& nominal_sigma1, const std::set<std::string>& available)
    : effect_(effect), nominal_(nominal), data_(data), options_(options), nominal_sigma1_(nominal_sigma1) {
  for (const std::string& s : effect.subsystems) {
    if (available.count(s)) subsystems_.insert(s);
  }
}

std::vector<double> CandidateObjective::toTheta(const double* x) const {
  std::vector<double> theta(effect_.params.size());
  for (std::size_t i = 0; i < theta.size(); ++i) theta[i] = effect_.params[i].log_scale ? std::exp(x[i]) : x[i];
  return theta;
}

std::vector<double> CandidateObjective::toFitSpace(const std::vector<double>& theta) const {
  std::vector<double> x(theta.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = effect_.params[i].log_scale ? std::log(theta[i]) : theta[i];
  return x;
}

ConfigChange CandidateObjective::changeFor(const std::vector<double>& theta) const {
  const CandidateEffect* effect = &effect_;
  return [effect, theta](SimConfig& c) { effect->apply(theta, c); };
}

SimConfig CandidateObjective::configFor(const std::vector<double>& theta) const {
  SimConfig c = nominal_;
  effect_.apply(theta, c);
  return c;
}

bool CandidateObjective::residuals(const std::vector<double>& theta, std::vector<double>* out) const {
  const ConfigChange change = changeFor(theta);
  if (!configFor(theta).problems().empty() || divergence(change) > 0.0) return false;
  replayResiduals(change, out);
  return true;
}

double CandidateObjective::loss(const std::vector<double>& theta) const {
  if (!configFor(theta).problems().empty()) return std::numeric_limits<double>::infinity();
  const ConfigChange change = changeFor(theta);
  if (const double d = divergence(change); d > 0.0) return kUnstableLoss * (1.0 + d);
  std::vector<double> r;
  replayResiduals(change, &r);
  return sumOfSquares(r);
}

void CandidateObjective::replayResiduals(const ConfigChange& change, std::vector<double>* out) const {
  const bool reuse = subsystems_.count("chassis") == 0;
  *out = fitResiduals(evaluate(change, data_, subsystems_, options_, reuse ? &nominal_sigma1_ : nullptr));
}

double CandidateObjective::divergence(const ConfigChange& change) const {
  for (const BoundedLoopRequirement& s : stable_on_) {
    const LoopDivergence d = boundsCheck(change, s);
    if (d.diverged) return std::clamp(1.0 - d.time / s.horizon, 1e-6, 1.0);
  }
  return 0.0;
}

}  // namespace diagnosis
}  // namespace lane_keeping
