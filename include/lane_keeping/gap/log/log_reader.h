#pragma once
/// Reads a log by its file type: CSV here; bags through the reader the ROS layer registers
/// (the core has no ROS dependency, so lk_gap links the bag reader and registers it at start-up).
#include <functional>
#include <string>

#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {

using BagLogReader = std::function<GapLog(const std::string& path)>;
/// Installs the reader used for *.bag files.
void registerBagLogReader(BagLogReader reader);
/// *.csv (any case) -> readCsvLog (with `mapping`); *.bag -> the registered bag reader (InputError if
/// none; a bag holds the suite's own topics, so a mapping is refused); anything else -> InputError
/// naming the file.
GapLog readLog(const std::string& path, const LogMapping& mapping = {});

}  // namespace lane_keeping
