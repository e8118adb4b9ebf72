#include "lane_keeping/gap/decision/how_far.h"

#include <cmath>
#include <limits>
#include <vector>

#include "lane_keeping/common/parallel_for.h"
#include "lane_keeping/gap/replay/closed_loop_replay.h"
#include "lane_keeping/gap/replay/subsystem_replay.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

void howFar(const CandidateFit* winner, const Evaluation& nominal_held,
            const std::vector<RunData>& runs, const DiagnosisOptions& options,
            GapReport* report, DiagnosisArtifacts* artifacts) {
  for (const auto& [name, score] : nominal_held.scores) {
    report->how_far.subsystems_before[name] = score.excess;
    report->how_far.subsystems_noise_reference[name] = score.reference;
  }
  for (const auto& [name, score] : (winner ? winner->heldout_scores : nominal_held.scores)) {
    report->how_far.subsystems_after[name] = score.excess;
  }
  if (!options.closed_loop) {
    // Not run: no gap to show (0 -> 0 read as a perfect match), and no overlay to draw.
    report->how_far.before = report->how_far.after = kNaN;
    std::string why;
    for (const RunData& run : runs) {
      why = replayUnavailable("tracker", run.log->log());
      if (!why.empty()) {
        why = "the logs cannot drive the closed loop: " + run.log->log().source + ": " + why;
        break;
      }
    }
    report->how_far.not_run = why.empty() ? "closed-loop replays switched off (DiagnosisOptions::closed_loop)" : why;
  } else {
    // Each run's nominal and corrected closed loops are independent: side by side on the threads
    // (each starts from the lateral velocity its run's chassis replay estimates at the log's start).
    std::vector<double> start_sigma1(runs.size(), kNaN);
    parallelFor(runs.size(), options.threads, [&](std::size_t i) {
      const Evaluation chassis = evaluate(nullptr, wholeLogs({runs[i]}, 0.0), {"chassis"}, options.replay);
      if (!chassis.sigma1.empty() && !chassis.sigma1[0].empty()) start_sigma1[i] = chassis.sigma1[0].front().second;
    });
    std::vector<ClosedLoopReplay> nominal(runs.size()), corrected(runs.size());
    parallelFor((winner ? 2 : 1) * runs.size(), options.threads, [&](std::size_t k) {
      const std::size_t i = k % runs.size();
      if (k < runs.size()) {
        nominal[i] = closedLoopReplay(*runs[i].config, *runs[i].log, start_sigma1[i]);
      } else {
        corrected[i] = closedLoopReplay(changed(*runs[i].config, winner->change), *runs[i].log, start_sigma1[i]);
      }
    });
    double before = 0.0, after = 0.0;
    int counted = 0;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const LogSignals& log = *runs[i].log;
      const ClosedLoopReplay& b = nominal[i];
      const ClosedLoopReplay& a = winner ? corrected[i] : b;
      if (!b.note.empty()) report->notes.push_back("nominal " + b.note);
      if (winner && !a.note.empty()) report->notes.push_back("corrected " + a.note);
      if (std::isfinite(b.gap) && std::isfinite(a.gap)) {
        before += b.gap * b.gap;
        after += a.gap * a.gap;
        ++counted;
      }
      if (artifacts != nullptr && i == 0) {
        artifacts->overlay_t = b.t;
        artifacts->overlay["y_real"] = {};
        for (double t : b.t) {
          artifacts->overlay["y_real"].push_back(log.at(LogSignals::kY, t));
          artifacts->overlay["yaw_rate_real"].push_back(log.at(LogSignals::kYawRate, t));
          artifacts->overlay["delta_real"].push_back(log.at(LogSignals::kDelta, t));
        }
        artifacts->overlay["y_nominal"] = b.y;
        artifacts->overlay["yaw_rate_nominal"] = b.yaw_rate;
        artifacts->overlay["delta_nominal"] = b.delta;
        if (winner) {
          auto pad = [&](std::vector<double> v) {
            v.resize(b.t.size(), kNaN);
            return v;
          };
          artifacts->overlay["y_corrected"] = pad(a.y);
          artifacts->overlay["yaw_rate_corrected"] = pad(a.yaw_rate);
          artifacts->overlay["delta_corrected"] = pad(a.delta);
        }
      }
    }
    report->how_far.before = counted ? std::sqrt(before / counted) : kNaN;
    report->how_far.after = counted ? std::sqrt(after / counted) : kNaN;
    if (counted == 0) report->how_far.not_run = "no closed-loop replay gave a gap (see the notes)";
  }
}

}  // namespace diagnosis
}  // namespace lane_keeping
