// Children started from their argument vector (common/child_process.h): an argument is one argument
// whatever it holds — a report directory named "x';touch F;'" ran `touch F` when pasted into a shell
// command — and a failure says what the child said (a quote in "O'Brien runs" broke the plotting with a
// misleading "python3-matplotlib?").
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "lane_keeping/common/child_process.h"

namespace lane_keeping {
namespace {

namespace fs = std::filesystem;

TEST(ChildProcess, AnArgumentReachesTheChildAsItIsAndRunsNothing) {
  const fs::path dir = fs::path(testing::TempDir()) / "lk_child_process";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string witness = (dir / "F").string();
  const std::string hostile = "rep/x';touch " + witness + ";' $(touch " + witness + ") `touch " + witness + "` O'Brien runs";
  const ChildResult r = runChild({"/usr/bin/printf", "%s", hostile}, true);
  ASSERT_TRUE(r.ok()) << r.failure();
  EXPECT_EQ(r.output, hostile);
  EXPECT_FALSE(fs::exists(witness));
}

TEST(ChildProcess, AFailureSaysWhatTheChildSaid) {
  const ChildResult r = runChild({"/bin/sh", "-c", "echo 'ModuleNotFoundError: No module named numpy' >&2; exit 3"});
  EXPECT_TRUE(r.started);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.exit_status, 3);
  EXPECT_EQ(r.failure(), "exit status 3: ModuleNotFoundError: No module named numpy");

  const ChildResult missing = runChild({"/nonexistent/python3", "x"});
  EXPECT_FALSE(missing.started);
  EXPECT_EQ(missing.failure(), "cannot start /nonexistent/python3: No such file or directory");

  const ChildResult killed = runChild({"/bin/sh", "-c", "kill -9 $$"});
  EXPECT_EQ(killed.signal, 9);
  EXPECT_NE(killed.failure().find("killed by signal 9"), std::string::npos) << killed.failure();
}

TEST(ChildProcess, ALongErrorOutputKeepsItsEnd) {
  // 200 kB on stderr and on stdout at once: both drained (no deadlock), the end of stderr kept.
  const ChildResult r = runChild({"/bin/sh", "-c",
                                  "i=0; while [ $i -lt 4000 ]; do echo line $i >&2; echo out $i; i=$((i+1)); done; "
                                  "echo last words >&2; exit 1"},
                                 true);
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_LE(r.error_output.size(), 8192u);
  EXPECT_NE(r.failure().find("last words"), std::string::npos);
  EXPECT_NE(r.output.find("out 3999"), std::string::npos);
}

}  // namespace
}  // namespace lane_keeping
