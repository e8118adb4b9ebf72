#include "lane_keeping/gap/bounded_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/gap/candidate_objective.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

LoopDivergence boundsCheck(SimConfig config, const BoundedLoopRequirement& r) {
  double& limit = config.simulation.divergence.max_steering_angle;
  limit = std::min(limit, r.max_steering_angle);
  return closedLoopDivergence(config, *r.log, kNaN, r.horizon, r.max_torque);
}

std::vector<BoundedLoopRequirement> stabilityRequirements(const CandidateObjective& objective, const std::vector<double>& theta,
                                                          const std::vector<Dataset>& train, const SimConfig& nominal,
                                                          std::string* note) {
  std::vector<const LogSignals*> logs;
  for (const Dataset& d : train) {
    if (std::find(logs.begin(), logs.end(), d.log.get()) == logs.end()) logs.push_back(d.log.get());
  }
  std::vector<BoundedLoopRequirement> requirements;
  for (const LogSignals* log : logs) {
    const double span = log->end() - log->start();
    double logged_angle = 0.0, logged_torque = 0.0;
    for (double delta : log->samples(LogSignals::kDelta)) logged_angle = std::max(logged_angle, std::fabs(delta));
    for (double torque : log->samples(LogSignals::kTorque)) logged_torque = std::max(logged_torque, std::fabs(torque));
    const BoundedLoopRequirement required{log, span, 1.5 * logged_angle + 0.02, 2.0 * logged_torque + 5.0};
    const LoopDivergence d = boundsCheck(objective.configFor(theta), required);
    if (!d.diverged || boundsCheck(nominal, required).diverged) continue;
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
