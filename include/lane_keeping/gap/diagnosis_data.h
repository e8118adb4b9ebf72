#pragma once
/// The data a diagnosis works on (diagnosis.h, step 1): each run's log as a continuous-time view with
/// its own configuration (gap_run.h) and the time segments used from it, and the split into training
/// and held-out data.
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/log/input_checks.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/replay_trace.h"

namespace lane_keeping {
namespace diagnosis {

/// A run ready for the replays: its log as a continuous-time view, and its configuration (with the
/// initial state estimated from the log where the configuration does not state it).
struct RunData {
  std::shared_ptr<const LogSignals> log;
  std::shared_ptr<const SimConfig> config;
  /// What estimateExcitationClock found when it did not keep the log's own clock (replay/excitation_clock.h).
  std::string clock_note;
  std::vector<InputCheck> input_checks;  ///< what is odd about the log (input_checks.h)
};

/// Each run ready for the replays, with its input checks. Throws InputError for a log the checks refuse
/// (refuseImplausibleLog), before any replay.
std::vector<RunData> prepareRuns(const std::vector<GapRun>& runs);

/// The subsystems no run can feed (every run must: data sets are replayed together), each with why —
/// the columns the first run lacking them does not have (replayUnavailable), or the input check that
/// rules the replay out: a stuck channel it reads, a sample rate too low for its band.
std::map<std::string, std::string> unavailableSubsystems(const std::vector<RunData>& runs);
/// The others.
std::set<std::string> availableSubsystems(const std::vector<RunData>& runs);

/// A run and the time segments of it that a data set uses.
struct Dataset {
  std::shared_ptr<const LogSignals> log;
  std::shared_ptr<const SimConfig> config;
  std::vector<TimeSegment> segments;
};

/// The start of a log (issue 47, kind 2). A run that starts with a large correction (an initial offset
/// of metres, a lane change under way) holds much of its excitation in its first seconds, and an effect
/// that acts only there (a torque limit the initial correction hits, a tire lag the transient shows) is
/// invisible anywhere else. A run *starts with a transient* when its first kStartTransientWindow seconds
/// hold at least kStartTransientShare of its excitation (the mean over the kinds of `excitations` of each
/// one's share) and at least kStartTransientRatio times their share of its duration. On the two benchmark
/// families: the runs from offsets of 1.5-3 m (shares 0.35-0.6), none of the runs that start on the lane
/// (at most 0.3, and at most 3.0 times their time share).
constexpr double kStartTransientWindow = 2.0;  ///< [s]
constexpr double kStartTransientShare = 0.3;
constexpr double kStartTransientRatio = 3.0;
/// For such a run the data begin kStartTransientLead after its first sample rather than start_margin (the
/// replays take their delayed inputs only where the log holds them: the tracker from start + tau1, the
/// actuator from start + tau2; the steering and chassis replays start from the logged state), and with
/// one run the window is cut on a grid of kStartSliver seconds into slivers that alternate between
/// training and held-out data (the first, from the lead, is training), so that both sides see the
/// transient. The 0.6 s margin and a block of at least min_block_length put it wholly into training: a
/// 48 N m limit cut by a 2 m correction in its first 0.5 s was "a gap the held-out data do not confirm".
constexpr double kStartSliver = 0.25;  ///< [s]
/// The first 0.1 s of such a run are the PID's answer to the step of its error at the first sample (the
/// P term's impulse, hundreds of N m for a few ms, and the steering loop's fast mode ringing: 17.6 and
/// 46 Hz at p = 1000), which a 100 Hz log cannot resolve: from the first sample, the steering replay of
/// a tire-lag log from a 3 m offset held 99.8 % of its excess in its first window (nrmse 2.13 against
/// 0.12 from 0.6 s), the training fits followed it, and that log and a heading mount's were lost.
constexpr double kStartTransientLead = 0.1;  ///< [s]
bool startsWithTransient(const LogSignals& log, const SimConfig& config);

/// Each run whole, from `margin` seconds after its start (at most kStartTransientLead if it starts with
/// a transient), less its holes (cutAtHoles).
std::vector<Dataset> wholeLogs(const std::vector<RunData>& runs, double margin);

/// The data sets' segments with each hole of their log's time axis (timeHoles, input_checks.h) cut out,
/// and `margin` seconds after it (the delayed inputs need history again, as at a log's start): the replays
/// integrate a segment with the inputs interpolated between samples, and across a hole that is an invented
/// input. Pieces shorter than kMinPieceBetweenHoles are dropped, and so is a data set left without any.
constexpr double kMinPieceBetweenHoles = 0.5;  ///< [s]
void cutAtHoles(std::vector<Dataset>* data, double margin);

/// Training and held-out data (DESIGN §5 "which"):
///  * held-out runs given: all training runs train, all held-out runs score;
///  * several runs, none held out: whole runs are held out — every other run in order of duration
///    (the longest trains), so each side sees complete manoeuvres;
///  * one run: alternating blocks (even train, odd held out) cut so that every kind of excitation lies
///    on both sides. Blocks are equal in "activity", half elapsed time and half the mean of the
///    normalised cumulative excitations: |steering rate|, |steering torque - its median|, |lateral
///    acceleration| (or V |yaw rate|) and |delta_des - delta|. Where the log is quiet the blocks are
///    about block_length long; a transient that holds much of an excitation (the initial correction of
///    an offset, a saturating lane change) is cut into short blocks (not below min_block_length) that
///    fall on both sides. Equal-time blocks put the first seconds of a run, often its strongest
///    excitation, wholly into training: an effect that shows only there (a torque limit hit by the
///    initial correction) was invisible on held-out data.
///  * options.fold == 1: the second fold, the two sides of the above swapped (for runs held out by the caller,
///    the caller swaps them: fold_pooling.h).
/// `coverage` gives, per excitation kind, the share of it that lies in held-out data.
struct DataSplit {
  std::vector<Dataset> train, held;
  std::vector<std::string> held_blocks, train_blocks;  ///< what each side holds ("whole runs", "blocks")
  std::string method;                       ///< "held-out runs", "whole runs" or "excitation-balanced blocks"
  std::map<std::string, double> coverage;   ///< excitation kind -> held-out share
};

DataSplit splitData(const std::vector<RunData>& train_runs, const std::vector<RunData>& held_runs,
                    const DiagnosisOptions& options);

/// Coarse data for a fit's first search (candidate_fit.h): each data set's segments cut into pieces of
/// `piece` seconds, of which every `stride`-th is kept (counted per data set from its first piece, so
/// every set keeps at least one and the sets stay in order, as the nominal sigma1 cache indexes them).
/// The pieces are spread over the whole log, so the coarse data see every part of the manoeuvre.
std::vector<Dataset> decimatedData(const std::vector<Dataset>& data, double piece, std::size_t stride);

/// The pieces of `piece` seconds that decimatedData cuts `data`'s segments into (a segment's last
/// piece may be shorter).
std::size_t pieceCount(const std::vector<Dataset>& data, double piece);

/// The coarse data of a fit (DiagnosisOptions::coarse_fit_stride): each data set decimated as above with
/// the stride max(`min_stride`, round(sqrt(n))) for its n pieces, so a set's coarse pieces grow as the
/// square root of its length (~sqrt(n)) and the coarse search's cost stops growing with the data while
/// its estimate still sharpens. Sets of up to 12 pieces (24 s at the 2 s chassis horizon, every log of
/// both benchmark families) keep the stride 3 as before; lk_bench_gap's 60 s log (18-20 training
/// pieces) takes 4, 5 pieces instead of 6-7 (issue 18: its coarse search was half of its fitting work).
std::vector<Dataset> coarseFitData(const std::vector<Dataset>& data, double piece, std::size_t min_stride);

/// The excitation kinds of a log, each as its magnitude at every sample (the names of DataSplit::coverage).
std::map<std::string, std::vector<double>> excitations(const LogSignals& log, const SimConfig& config);

}  // namespace diagnosis
}  // namespace lane_keeping
