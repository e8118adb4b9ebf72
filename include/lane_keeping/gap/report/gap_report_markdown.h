#pragma once
/// The human-readable gap report: DIR/report.md (GitHub-flavoured Markdown).
///
/// Sections, in order: verdict (effect, confidence, held-out shrink, reason, confusable effects) with the
/// config overlay that adds the effect; input checks (what is odd about the logs: holes, stuck channels, rates,
/// units, speed); ranking table (effect, parameters +- 1 sigma, held-out gap before/after,
/// shrink, score); where (subsystem table, top time windows in seconds since their log's first sample,
/// frequency-band shares, operating regimes); how far (closed-loop — or "not run (why)" — and per-subsystem
/// held-out gap before/after); data (logs, rows used/skipped, notes);
/// plots. Image links to DIR/residuals.png, spectrum.png, overlay.png and ranking.png are written only for the
/// files that exist when this is called, so run scripts/gap_report_plots.py DIR first.
/// Non-finite numbers print as "n/a".
#include <string>

#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {

/// Writes DIR/report.md (creates DIR if needed). Throws InputError if it cannot be written. `shown_dir`
/// is the directory the text names (where the report will be read: a staging directory is moved there,
/// report_directory.h); "" = DIR.
void writeGapReportMarkdown(const std::string& dir, const GapReport& report, const std::string& shown_dir = "");

}  // namespace lane_keeping
