// Which file a path names (common/file_identity.h): an output that is one of the inputs, a held-out log
// that is the training log, by another spelling or through a link; inputs that are not files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/file_identity.h"

namespace lane_keeping {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir / "sub");
  return dir;
}

TEST(FileIdentity, TheSameFileByAnySpelling) {
  const fs::path dir = freshDir("lk_file_identity");
  const std::string a = (dir / "a.csv").string();
  std::ofstream(a) << "t\n";
  std::ofstream(dir / "b.csv") << "t\n";  // the same content, another file
  fs::create_symlink(a, dir / "link.csv");
  fs::create_hard_link(a, dir / "hard.csv");
  EXPECT_TRUE(sameFile(a, (dir / "sub" / ".." / "a.csv").string()));
  EXPECT_TRUE(sameFile(a, (dir / "." / "a.csv").string()));
  EXPECT_TRUE(sameFile(a, (dir / "link.csv").string()));
  EXPECT_TRUE(sameFile(a, (dir / "hard.csv").string()));
  EXPECT_FALSE(sameFile(a, (dir / "b.csv").string()));
  // Not there yet (an output): compared by path.
  EXPECT_TRUE(sameFile((dir / "new.csv").string(), (dir / "sub" / ".." / "new.csv").string()));
  EXPECT_FALSE(sameFile((dir / "new.csv").string(), a));
}

TEST(FileIdentity, InsideADirectory) {
  const fs::path dir = freshDir("lk_file_inside");
  EXPECT_TRUE(isInside((dir / "sub" / "x.csv").string(), dir.string()));
  EXPECT_TRUE(isInside((dir / "sub").string(), (dir / "sub/").string()));
  EXPECT_FALSE(isInside((dir / "subway.csv").string(), (dir / "sub").string()));
  EXPECT_FALSE(isInside(dir.string(), (dir / "sub").string()));
}

TEST(FileIdentity, WhyAPathIsNotARegularFile) {
  const fs::path dir = freshDir("lk_file_kind");
  std::ofstream(dir / "f.yaml") << "a: 1\n";
  fs::create_symlink(dir / "gone.csv", dir / "dangling.csv");
  EXPECT_EQ(whyNotRegularFile((dir / "f.yaml").string()), "");
  EXPECT_EQ(whyNotRegularFile(dir.string()), "is a directory, not a file");
  EXPECT_EQ(whyNotRegularFile("/dev/zero"), "is a character device, not a regular file");
  EXPECT_EQ(whyNotRegularFile((dir / "none").string()), "does not exist");
  EXPECT_EQ(whyNotRegularFile((dir / "dangling.csv").string()),
            "is a dangling symbolic link to '" + (dir / "gone.csv").string() + "'");
}

TEST(FileIdentity, AnOutputThatIsAnInputIsRefused) {
  const fs::path dir = freshDir("lk_file_output");
  const std::string config = (dir / "my.yaml").string();
  std::ofstream(config) << "vehicle:\n  mass: 1100\n";
  fs::create_symlink(config, dir / "alias.yaml");
  try {
    refuseOutputAmongInputs({"--out", (dir / "alias.yaml").string()}, {{"--config", config}});
    FAIL() << "an output that is the configuration was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("is the file given as --config " + config), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(refuseOutputAmongInputs({"--out", (dir / "run.csv").string()}, {{"--config", config}}));
  // A directory output replaced as a whole may not hold an input.
  EXPECT_THROW(refuseOutputAmongInputs({"--report", dir.string()}, {{"--config", config}}, true), UsageError);
  EXPECT_NO_THROW(refuseOutputAmongInputs({"--report", (dir / "sub").string()}, {{"--config", config}}, true));
}

}  // namespace
}  // namespace lane_keeping
