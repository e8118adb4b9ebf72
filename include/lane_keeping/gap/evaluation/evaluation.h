#pragma once
/// How a configuration scores on data (diagnosis.h, steps 2-3): the subsystem replays over data sets
/// with their scores (gap_metrics.h), the combined gap, the noise-only reference that the gap is net
/// of, the residual vector the fits minimise, and the held-out evidence of a candidate.
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/evaluation/config_change.h"
#include "lane_keeping/gap/evaluation/gap_metrics.h"
#include "lane_keeping/gap/evaluation/residual_structure.h"
#include "lane_keeping/gap/replay/subsystem_replay.h"

namespace lane_keeping {
namespace diagnosis {

/// Replays of a configuration over data sets, traces concatenated across them.
struct Evaluation {
  std::map<std::string, SubsystemReplay> replays;
  std::map<std::string, SubsystemScore> scores;
  std::vector<std::vector<std::pair<double, double>>> sigma1;  ///< chassis estimate per data set
  /// Per subsystem: the index in its (concatenated) traces where each data set's samples start.
  std::map<std::string, std::vector<std::size_t>> starts;
};

using Sigma1Cache = std::vector<std::vector<std::pair<double, double>>>;

/// Replays `subsystems` over the data sets, each under its run's configuration with `change` applied
/// (empty: as configured). The steering replay takes sigma1 from this configuration's chassis replay,
/// or from `sigma1` when the chassis is not re-run.
Evaluation evaluate(const ConfigChange& change, const std::vector<Dataset>& data, const std::set<std::string>& subsystems,
                    const ReplayOptions& options, const Sigma1Cache* sigma1 = nullptr);

/// The evaluation of `first`'s data sets followed by `second`'s, from theirs: evaluate(change, A ++ B,
/// ...) is concatenated(evaluate(change, A, ...), evaluate(change, B, ...)), the same traces, breaks,
/// starts and scores, without replaying A and B again (the diagnosis's "where" report of all the data).
Evaluation concatenated(Evaluation first, const Evaluation& second);

/// `base` with the subsystems `changed` replayed (the same data sets) in their place: the evaluation of a
/// change that alters only those, from the base's and its own (the chassis's lateral velocity estimate
/// with the chassis).
Evaluation overlaid(Evaluation base, const Evaluation& changed);

/// Every subsystem name (subsystemNames()).
std::set<std::string> allSubsystems();

/// Combined gap with `changed` scores replacing the nominal ones where present (each keeps the
/// nominal score's noise reference: it belongs to the data, not to the model).
double gapOf(const std::map<std::string, SubsystemScore>& nominal, const std::map<std::string, SubsystemScore>& changed);

/// The residual structure (residual_structure.h) of every replayed subsystem, each against its input:
/// steering the logged torque, chassis the logged steering angle, tracker the logged lateral position
/// tau1 back, actuator the logged error delta_des - delta.
std::map<std::string, ResidualStructure> residualStructures(const Evaluation& ev, const std::vector<Dataset>& data);

/// Stores the reference excess of each subsystem in `scores`.
void setReference(std::map<std::string, SubsystemScore>& scores, const std::map<std::string, double>& reference);

/// Residual vector for the fit: each trace's residuals / sqrt(its sample count), so that the
/// objective is the sum over traces of mean squares (the sum of nrmse^2).
std::vector<double> fitResiduals(const Evaluation& ev);

double sumOfSquares(const std::vector<double>& r);

/// Held-out evidence for a candidate: the reduction of sum_traces N (nrmse^2) / floor^2 that it brings,
/// with the nominal floors — a chi-square-like count of how many noise variances of mismatch it
/// removes. Noise fitted on training data does not carry over to held-out data, so this stays near
/// (or below) zero for a candidate that explains nothing.
double evidenceOf(const std::map<std::string, SubsystemScore>& before, const std::map<std::string, SubsystemScore>& after);

}  // namespace diagnosis
}  // namespace lane_keeping
