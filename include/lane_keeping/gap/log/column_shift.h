#pragma once
/// Per-column time shifts of a log mapping (log_mapping.h, `shift:`): a channel logged late (a bus or
/// sensor latency: a race car's yaw-rate column lagged its steering and heading by 0.21-0.23 s, which the
/// diagnosis otherwise "explains" as slicks at a third of their stiffness, issue 46) is moved back onto
/// the log's time base, so that every column of a row refers to the same instant.
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_mapping.h"

namespace lane_keeping {

/// For every mapped column with a shift s (seconds; the column was logged s late), replaces its value at
/// each row's time t by the raw column at t + s, interpolated linearly between the two rows around it
/// (across rows skipped for NaN too). Rows where t + s falls outside the log for some shifted column
/// (the first s seconds for a negative shift, the last s for a positive one) have no value there and are
/// dropped, every column alike; the log's notes say which column moved, by how much, and how many rows
/// went. A shifted column the log does not hold is noted and ignored. Throws InputError naming the log,
/// the mapping entry (file:line) and the shift when the shifts leave fewer than two rows.
void applyColumnShifts(GapLog* log, const LogMapping& mapping);

}  // namespace lane_keeping
