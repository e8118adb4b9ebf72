// A report directory written as a whole (report_directory.h): the directory holds one run's complete
// report or the previous one, never a mix; a second writer is refused while the first runs; a directory
// holding anything but a report, or that cannot be written, is refused before the work.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/report/report_directory.h"

namespace lane_keeping {
namespace {

namespace fs = std::filesystem;

fs::path freshParent(const std::string& name) {
  const fs::path parent = fs::path(testing::TempDir()) / name;
  fs::remove_all(parent);
  fs::create_directories(parent);
  return parent;
}

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A "report" of run `id`: every file the same id.
void writeReport(const std::string& dir, const std::string& id) {
  for (const char* name : {"report.json", "report.md", "residuals.csv", "overlay.png"}) std::ofstream(fs::path(dir) / name) << id;
}

void expectWholeReport(const fs::path& dir, const std::string& id) {
  for (const char* name : {"report.json", "report.md", "residuals.csv", "overlay.png"}) {
    EXPECT_EQ(read(dir / name), id) << name;
  }
}

TEST(ReportDirectory, ARunReplacesThePreviousReportAsAWhole) {
  const fs::path parent = freshParent("lk_report_dir_whole");
  const std::string target = (parent / "rep").string();
  {
    ReportDirectory first(target);
    EXPECT_FALSE(fs::exists(target));  // nothing there until the report is complete
    EXPECT_EQ(fs::path(first.staging()).parent_path(), parent);
    writeReport(first.staging(), "run 1");
    first.publish();
  }
  expectWholeReport(target, "run 1");
  {
    ReportDirectory second(target);
    writeReport(second.staging(), "run 2");
    std::ofstream(fs::path(second.staging()) / "ranking.png") << "run 2";
    expectWholeReport(target, "run 1");  // the previous report stays whole while the next is written
    second.publish();
  }
  expectWholeReport(target, "run 2");
  EXPECT_EQ(read(parent / "rep" / "ranking.png"), "run 2");
  // Nothing left beside it: no staging directory, no lock, no previous report.
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(parent)) left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"rep"});
}

TEST(ReportDirectory, AnInterruptedRunLeavesThePreviousReport) {
  const fs::path parent = freshParent("lk_report_dir_interrupted");
  const std::string target = (parent / "rep").string();
  {
    ReportDirectory first(target);
    writeReport(first.staging(), "run 1");
    first.publish();
  }
  std::string abandoned;
  {
    ReportDirectory second(target);
    abandoned = second.staging();
    std::ofstream(fs::path(second.staging()) / "report.json") << "run 2";  // then the run fails
  }
  expectWholeReport(target, "run 1");
  EXPECT_FALSE(fs::exists(abandoned));
  // A run killed outright leaves its staging directory; the next run into the directory removes it.
  const fs::path stale = parent / ".rep.partial-killed";
  fs::create_directories(stale);
  {
    ReportDirectory third(target);
    EXPECT_FALSE(fs::exists(stale));
  }
}

TEST(ReportDirectory, ASecondWriterIsRefusedWhileTheFirstRuns) {
  const fs::path parent = freshParent("lk_report_dir_two");
  const std::string target = (parent / "rep").string();
  ReportDirectory first(target);
  try {
    ReportDirectory second((parent / "." / "rep").string());  // another spelling of the same directory
    FAIL() << "two writers into one report directory";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("another run is writing a report there"), std::string::npos) << e.what();
  }
  writeReport(first.staging(), "run 1");
  first.publish();
  expectWholeReport(target, "run 1");
}

TEST(ReportDirectory, ADirectoryHoldingOtherFilesOrUnwritableIsRefusedUpFront) {
  const fs::path parent = freshParent("lk_report_dir_refused");
  fs::create_directories(parent / "mine");
  std::ofstream(parent / "mine" / "notes.txt") << "keep me";
  try {
    ReportDirectory report((parent / "mine").string());
    FAIL() << "a directory of the user's files would be replaced";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("holds 'notes.txt', which is not part of a gap report"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read(parent / "mine" / "notes.txt"), "keep me");
  std::ofstream(parent / "a_file") << "x";
  EXPECT_THROW(ReportDirectory((parent / "a_file").string()), UsageError);            // not a directory
  EXPECT_THROW(ReportDirectory((parent / "a_file" / "rep").string()), InputError);    // its parent cannot be made
  EXPECT_NO_THROW(ReportDirectory((parent / "new" / "deeper" / "rep").string()));    // parents are created
}

TEST(ReportDirectory, APreviousReportThatCannotBeReplacedIsFoundUpFront) {
  // Found when the report was written, after the whole diagnosis. (Root writes anywhere, but not into an
  // immutable directory.)
  const fs::path parent = freshParent("lk_report_dir_immutable");
  fs::create_directories(parent / "rep");
  std::ofstream(parent / "rep" / "report.json") << "run 1";
  if (std::system(("chattr +i '" + (parent / "rep").string() + "' 2>/dev/null").c_str()) != 0) {
    GTEST_SKIP() << "chattr +i is not available here";
  }
  try {
    ReportDirectory report((parent / "rep").string());
    ADD_FAILURE() << "an immutable report directory was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the report could not replace the previous one"), std::string::npos) << e.what();
  }
  std::system(("chattr -i '" + (parent / "rep").string() + "'").c_str());
}

}  // namespace
}  // namespace lane_keeping
