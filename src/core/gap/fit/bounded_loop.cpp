#include "lane_keeping/gap/fit/bounded_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/gap/fit/candidate_objective.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

LoopDivergence boundsCheck(const ConfigChange& change, const BoundedLoopRequirement& r) {
  SimConfig config = changed(*r.config, change);
  double& limit = config.simulation.divergence.max_steering_angle;
  limit = std::min(limit, r.max_steering_angle);
  return closedLoopDivergence(config, *r.log, kNaN, r.horizon, r.max_torque);
}

bool NominalBounds::leaves(const BoundedLoopRequirement& r) {
  Entry* entry = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = entries_[Key{r.log, r.config, r.horizon, r.max_steering_angle, r.max_torque}];
    if (!slot) slot = std::make_unique<Entry>();
    entry = slot.get();
  }
  std::call_once(entry->once, [&] { entry->leaves = boundsCheck(nullptr, r).diverged; });
  return entry->leaves;
}

std::vector<BoundedLoopRequirement> stabilityRequirements(const CandidateObjective& objective, const std::vector<double>& theta,
                                                          const std::vector<Dataset>& train, std::string* note,
                                                          NominalBounds* nominal) {
  std::vector<const Dataset*> runs;  // each run once (a log split into blocks appears in one data set)
  for (const Dataset& d : train) {
    if (std::none_of(runs.begin(), runs.end(), [&](const Dataset* r) { return r->log == d.log; })) runs.push_back(&d);
  }
  std::vector<BoundedLoopRequirement> requirements;
  for (const Dataset* run : runs) {
    const LogSignals* log = run->log.get();
    const double span = log->end() - log->start();
    double logged_angle = 0.0, logged_torque = 0.0;
    for (double delta : log->samples(LogSignals::kDelta)) logged_angle = std::max(logged_angle, std::fabs(delta));
    for (double torque : log->samples(LogSignals::kTorque)) logged_torque = std::max(logged_torque, std::fabs(torque));
    const BoundedLoopRequirement required{log, run->config.get(), span, 1.5 * logged_angle + 0.02, 2.0 * logged_torque + 5.0};
    const LoopDivergence d = objective.bounds(theta, required);
    if (!d.diverged || (nominal ? nominal->leaves(required) : boundsCheck(nullptr, required).diverged)) continue;
    requirements.push_back(required);
    if (!note->empty()) continue;
    std::ostringstream os;
    os << "the least-squares fit (";
    for (std::size_t j = 0; j < theta.size(); ++j) {
      os << (j ? ", " : "") << objective.effect().params[j].name << " " << formatNumber(theta[j]);
    }
    os << ") makes the closed loop diverge on " << log->log().source << " (" << d.message << ")";
    *note = os.str();
  }
  return requirements;
}

}  // namespace diagnosis
}  // namespace lane_keeping
