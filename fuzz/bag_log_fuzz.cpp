// Fuzz target: the bag reader lk_gap registers with registerBagLogReader (gap/log/log_reader.h), readBagLog
// (src/nodes/bag_log_reader.h), through readLog as lk_gap --log FILE.bag calls it. Feeds: the input as a
// .bag file (the seeds are small bags of the suite's topics; libFuzzer mutates them). Asserts: a GapLog
// of at least 10 rows with t strictly increasing, or an InputError naming the bag; rosbag's own
// exceptions (rosbag::BagException, ros::serialization's StreamOverrunException, ...) escaping the
// reader, a crash, a hang or a sanitizer report are findings.
#include "bag_log_reader.h"
#include "fuzz_support.h"
#include "lane_keeping/gap/log/log_reader.h"

#include <rosbag/bag.h>

using namespace lane_keeping;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool registered = [] {
    registerBagLogReader([](const std::string& path) { return readBagLog(path); });
    return true;
  }();
  (void)registered;
  // Every rosbag::Bag loads its encryptor plugin through pluginlib, and the last one destroyed unloads it:
  // a dlopen and a dlclose per input, which (with the leak check libFuzzer then runs, as the loader's
  // allocations do not balance within the input) made 3/4 of an execution. One Bag kept for the process
  // keeps the plugin library loaded; what each input exercises is unchanged.
  static const rosbag::Bag keep_plugin_loaded;
  (void)keep_plugin_loaded;
  const std::string path = fuzz::writeFile("log.bag", std::string(reinterpret_cast<const char*>(data), size));
  fuzz::expectResultOrSuiteError(
      [&] {
        const GapLog log = readLog(path);
        if (log.size() < 10) fuzz::finding("a bag with fewer than 10 rows was accepted");
        for (std::size_t i = 1; i < log.size(); ++i) {
          if (!(log.t[i] > log.t[i - 1])) fuzz::finding("t not strictly increasing");
        }
      },
      path);
  return 0;
}
