#pragma once
/// Delay and gain candidates scored on the steering loop's modes (issue 47, kind 3): where a log rings
/// (loop_ringing.h) and no candidate explains the gap by the replays, which cannot follow a mode that
/// lies above the log's Nyquist frequency, the seed paper's own tool decides: the closed loop's
/// characteristic roots (Beregi eq 21, dde_spectrum.h), here of the loop linearised about straight
/// driving (closed_loop_linearization.h) with the candidate's fitted parameters.
///
/// The rule. A log's ringing at f (as sampled at rate fs) is the loop's mode lambda = -sigma + i 2 pi f0
/// when f0 aliases to f within one bin of the band (|alias(f0) - f| <= fs / 64, the peak bin's centre
/// lies within half a bin of a tone) and the mode is lightly damped: its envelope falls by 1/e over at
/// least kModalCycles cycles (sigma <= f0 / kModalCycles; a quality factor pi f0 / sigma of 9 or more), as a mode must to ring visibly over
/// seconds of sensor noise (the independent family's +1.7 ms log: 129.4 Hz, sigma 7.1 1/s, 18 cycles;
/// the nominal's fast mode lies far left). A candidate has the modal evidence when
///   - the nominal's roots hold no such mode (else the ringing is not the candidate's to explain),
///   - its fit removes at least min_shrink of the training gap (the replays agree where they can),
///   - some value of one of its parameters within kModalSigmas standard errors of its fit (the others
///     at their fits) gives the loop such a mode, its linearised loop stable there (a bounded log cannot
///     be an unstable loop; the least-squares fit itself may lie beyond the margin).
/// The verdict names a candidate on this evidence where it alone has it and the replays name nothing,
/// also where their test does not detect the gap: the ringing is a test of its own (verdict.h).
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/evaluation/loop_ringing.h"
#include "lane_keeping/gap/fit/candidate_fit.h"

namespace lane_keeping {
namespace diagnosis {

/// Cycles over which a ringing mode's envelope falls by 1/e, at least.
constexpr double kModalCycles = 3.0;
/// The scan of a parameter: its fit +- this many standard errors.
constexpr double kModalSigmas = 3.0;
/// Values per parameter in the scan (odd: the fit itself is one).
constexpr int kModalScanPoints = 31;

/// A root of the loop that a ringing may be.
struct RingingMode {
  double frequency = 0.0;  ///< [Hz] the root's, Im lambda / 2 pi
  double decay = 0.0;      ///< [1/s] -Re lambda
  double alias = 0.0;      ///< [Hz] where a log at the ringing's rate sees it
  double error = 0.0;      ///< [Hz] |alias - the ringing's frequency|
};

/// [Hz] where a log sampled at `rate` sees a tone of `frequency`: in [0, rate / 2].
double aliasedFrequency(double frequency, double rate);

/// The lightly damped root of `config`'s linearised loop nearest to `ringing` in alias, within one bin;
/// false where there is none, the loop is unstable (a bounded log cannot be it) or cannot be linearised.
bool ringingMode(const SimConfig& config, const LoopRinging& ringing, RingingMode* mode);

/// A candidate with the modal evidence for a ringing.
struct ModalSupport {
  std::string effect, form;  ///< as in the ranking (form: the fit's own, without tied forms)
  std::string parameter;     ///< the one scanned
  std::size_t index = 0;     ///< its index among the effect's parameters
  double fitted = 0.0, sigma = 0.0;  ///< its replay fit and standard error
  double modal = 0.0;        ///< the value of the scan whose mode lies nearest the ringing
  RingingMode mode;          ///< that mode
  LoopRinging ringing;
  std::string label() const { return form.empty() ? effect : effect + " (" + form + ")"; }
};

/// Every candidate (of `fits`, changing `subsystem`) with the modal evidence for one of `ringings`, at most
/// one entry per candidate (the ringing and parameter its mode matches best), on up to `threads` threads.
/// Appends to `notes` what each ringing's scan found.
std::vector<ModalSupport> modalSupport(const std::vector<CandidateFit>& fits, const SimConfig& nominal,
                                       const std::vector<LoopRinging>& ringings, const std::string& subsystem,
                                       double min_shrink, int threads, std::vector<std::string>* notes);

/// `fit` with the scanned parameter at its modal value: what a verdict named on the modes reports and replays
/// in closed loop (the replay fit itself may lie beyond the margin), its config and change rewritten.
CandidateFit atModalValue(const CandidateFit& fit, const ModalSupport& support, const SimConfig& nominal);

/// What the verdict's reason says of it.
std::string modalReason(const ModalSupport& support);

}  // namespace diagnosis
}  // namespace lane_keeping
