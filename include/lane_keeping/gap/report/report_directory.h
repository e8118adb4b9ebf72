#pragma once
/// A report directory written as a whole (lk_gap --report DIR). The report (report.json, report.md, the
/// series behind the plots, the plots) is written into a staging directory beside DIR and moved into
/// place in one rename, so DIR always holds one run's complete report or the previous one: an
/// interrupted run leaves the previous report as it was (and a hidden staging directory, removed by the
/// next run into DIR), never report.json of one run beside the plots of another. A lock beside DIR
/// (`.DIR.lock`, flock) refuses a second writer while the first runs: two concurrent runs into one
/// directory used to both exit 0, one report lost.
///
/// DIR may be new, empty, or hold a previous report; a directory holding anything else (another
/// program's files, a subdirectory, an input of the run) is refused, since the move replaces it as a
/// whole.
#include <string>
#include <vector>

namespace lane_keeping {

class ReportDirectory {
 public:
  /// The files a report directory may hold: what lk_gap writes there.
  static const std::vector<std::string>& reportFiles();

  /// Checks `target` and prepares its staging directory, before any work: creates the parent
  /// directories, takes the lock, removes stale staging directories of earlier interrupted runs.
  /// Throws UsageError if `target` is not a directory, holds files that are not a report's, or another
  /// process holds the lock; InputError if the parent cannot be created or written.
  explicit ReportDirectory(const std::string& target);
  ~ReportDirectory();
  ReportDirectory(const ReportDirectory&) = delete;
  ReportDirectory& operator=(const ReportDirectory&) = delete;

  /// Where the report is written until publish().
  const std::string& staging() const { return staging_; }
  /// The directory as the user named it.
  const std::string& target() const { return target_; }

  /// Moves the staging directory to the target: exchanged with the previous report in one rename
  /// (renameat2 RENAME_EXCHANGE) and the previous removed; a plain rename when there was none. Throws
  /// InputError if the move fails (the previous report is then left as it was).
  void publish();

 private:
  void releaseLock();
  std::string target_;     ///< as given
  std::string resolved_;   ///< the canonical path the rename works on
  std::string staging_;
  std::string lock_path_;
  int lock_fd_ = -1;
  bool published_ = false;
};

}  // namespace lane_keeping
