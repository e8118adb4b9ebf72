#pragma once
/// Holes in a log's time axis (issue 48): rows missing, or skipped for NaN, over more than a few samples.
/// The replays must not integrate across one, nor the derivatives and noise estimates of the log's
/// continuous-time view (log_signals.h) reach across it: both would invent what the car did while nothing
/// was logged.
#include <cstddef>
#include <utility>
#include <vector>

#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {

/// A hole: a step of the time axis longer than kHoleSteps median steps. A row skipped for NaN makes a step
/// of two, a bus log's jitter a fraction of one.
constexpr double kHoleSteps = 5.0;

struct TimeHole {
  double t0 = 0.0, t1 = 0.0;  ///< [s] the samples before and after the hole
};

/// The median of a time axis's steps (0 with fewer than two samples): the log's sampling interval, which
/// a hole, a jittered stamp or a dropped row does not move (GapLog::medianStep is this of its t).
double medianTimeStep(const std::vector<double>& t);

/// The holes of a time axis (strictly increasing), in order.
std::vector<TimeHole> timeHoles(const std::vector<double>& t);
inline std::vector<TimeHole> timeHoles(const GapLog& log) { return timeHoles(log.t); }

/// The index ranges [begin, end) of `t` between its holes, in order, covering every sample. A stretch of
/// fewer than kMinStretch samples (too few for a derivative's window) is joined to the one before it (the
/// first to the one after).
constexpr std::size_t kMinStretch = 5;
std::vector<std::pair<std::size_t, std::size_t>> holeFreeStretches(const std::vector<double>& t);

}  // namespace lane_keeping
