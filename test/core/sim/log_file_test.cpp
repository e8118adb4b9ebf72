// Writing a run's log: a full disk is an error naming the file, not a silently short log.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/sim/log_row.h"

namespace lane_keeping {
namespace {

TEST(LogFile, AFullDiskIsAnErrorNamingTheFile) {
  // /dev/full accepts the open and fails every write with ENOSPC; the stream buffers, so the failure
  // shows only when the buffer goes out (at the latest at close): 1,000 rows are ~300 kB, a few
  // buffers' worth, and 2 rows fit in one buffer (the case the close must catch).
  for (const std::size_t n : {std::size_t{2}, std::size_t{1000}}) {
    const std::vector<LogRow> rows(n);
    try {
      writeLogCsv("/dev/full", rows);
      FAIL() << "no error writing " << n << " rows to /dev/full";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("/dev/full"), std::string::npos) << what;
      EXPECT_NE(what.find("disk full"), std::string::npos) << what;
    }
  }
}

TEST(LogFile, AWrittenLogHasAHeaderAndEveryRow) {
  const std::string path = testing::TempDir() + "lk_log_file_test.csv";
  writeLogCsv(path, std::vector<LogRow>(7));
  std::ifstream in(path);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) ++lines;
  EXPECT_EQ(lines, 8);
}

}  // namespace
}  // namespace lane_keeping
