#pragma once
/// How far the gap shrinks once the winning effect is added (diagnosis.h, step 4; DESIGN §5 question 3):
/// the held-out excess of every subsystem before and after, and the closed-loop replay of whole runs
/// with the nominal and the corrected configuration.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/report/diagnosis_artifacts.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// The closed loop's net shrink below this share of the held-out replays' shrink: it "still misses".
constexpr double kClosedLoopShareOfShrink = 0.5;
/// The nominal's net closed-loop gap must reach this share of the noise floor for the note: below it the
/// closed loop hardly sees the effect (the floor's estimate is good to ~0.25 of itself in the net).
constexpr double kClosedLoopVisible = 0.5;

/// The lateral velocity each run's closed loop starts from: its chassis replay's estimate at the log's start
/// (NaN where it gives none). Run on options.threads threads.
std::vector<double> closedLoopStarts(const std::vector<RunData>& runs, const DiagnosisOptions& options);

/// What a perfect model's closed-loop replay of `log` still leaves of each channel's gap (y, yaw rate, delta):
/// closedLoopNoiseFloor at the log's white noise levels, read from the upper half of each channel's band.
std::array<double, 3> closedLoopFloor(const LogSignals& log);

/// A note where a verdict named by the replays, led by a physical effect, shrinks the closed-loop gap net of
/// noise by less than kClosedLoopShareOfShrink of its held-out shrink while the closed loop sees the gap
/// (kClosedLoopVisible) — issue 47, kind 7: a smooth tanh friction fitted to a kingpin friction's stick
/// plateaus removed 95 % open loop and 16 % in closed loop; "" otherwise.
std::string closedLoopStillMisses(const GapReport& report);

/// The closed loop contradicts the verdict: with the named effects the held-out runs' closed-loop replay is
/// farther from them than the nominal's, net of the logs' noise, by more than kClosedLoopVisible of the noise
/// floor — the change the closed loop would see at all. The replays took the log's own inputs and found a
/// shape that fits them (the candidates' out-of-list dead bands, fitted as tanh friction: 54 % held out),
/// but a simulation with it drives farther from the car (their net closed-loop gaps 0.034 -> 0.048 and
/// 0.043 -> 0.062, 1.14 and 0.80 of their floors; no right verdict of either benchmark family is worse by more
/// than 0.07 of its floor). Returns the verdict's reason for `unexplained`, or "" where it is not
/// contradicted (no closed-loop replay, or a verdict already unexplained).
std::string closedLoopContradicts(const GapReport& report);

/// Fills report->how_far: per-subsystem held-out excess before (`nominal_held`) and after (`winner`'s
/// held-out scores; the nominal's when there is no winner), and — if options.closed_loop — the RMS over
/// `runs` of the closed-loop replay gap with each run's configuration and with the winner added. Notes on
/// failed or diverged replays go to report->notes; the first run's overlays to `artifacts` (may be null).
/// The closed-loop gaps also net of the logs' noise (how_far.noise_floor, net_before, net_after), and the
/// note closedLoopStillMisses gives.
void howFar(const CandidateFit* winner, const Evaluation& nominal_held, const std::vector<RunData>& runs,
            const DiagnosisOptions& options,
            GapReport* report, DiagnosisArtifacts* artifacts);

}  // namespace diagnosis
}  // namespace lane_keeping
