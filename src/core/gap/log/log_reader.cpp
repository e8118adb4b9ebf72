#include "lane_keeping/gap/log/log_reader.h"

#include <algorithm>
#include <cctype>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {
BagLogReader& bagReader() {
  static BagLogReader reader;
  return reader;
}
std::string lowerExtension(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}
}  // namespace

void registerBagLogReader(BagLogReader reader) { bagReader() = std::move(reader); }

GapLog readLog(const std::string& path, const LogMapping& mapping) {
  const std::string ext = lowerExtension(path);
  if (ext == "csv") return readCsvLog(path, mapping);
  if (ext == "bag") {
    if (!mapping.empty()) {
      throw ConfigError(path + ": a bag holds the suite's own topics; the log mapping " + mapping.source +
                        " applies to CSV logs only");
    }
    if (!bagReader()) throw InputError(path + ": reading bags needs lk_gap built with rosbag support");
    return bagReader()(path);
  }
  throw InputError(path + ": unknown log type (expected .csv or .bag)");
}

}  // namespace lane_keeping
