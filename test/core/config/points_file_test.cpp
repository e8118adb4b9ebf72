// readPointsCsv (points_file.h): a lane from a map, parsed in blocks of the file where the lines lie.
// The edges of that scheme - a line cut by a block's end, a last line without a newline, CRLF endings, a
// line longer than a block, a pipe that cannot be read twice - each read the same points as a plain
// line-by-line reading of the same text; and a bad line is named by its number wherever it falls.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lane_keeping/config/points_file.h"

namespace lane_keeping {
namespace {

std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::vector<Point2> read(const std::string& path) {
  std::vector<Point2> points;
  std::string error;
  EXPECT_TRUE(readPointsCsv(path, &points, &error)) << error;
  return points;
}

/// n points "x,y" with varied lengths (so that lines straddle the 64 KiB blocks at every offset).
std::string lane(int n, const std::string& newline, std::vector<Point2>* expected) {
  std::ostringstream text;
  text << "x,y" << newline;
  for (int i = 0; i < n; ++i) {
    const Point2 p{0.5 * i, (i % 7) * 0.125 - 1e-3 * (i % 13)};
    expected->push_back(p);
    text.precision(17);
    text << p[0] << "," << p[1] << newline;
    if (i % 1000 == 0) text << "# metre " << i / 2 << newline;
  }
  return text.str();
}

TEST(PointsFile, ManyBlocksReadTheSamePointsWithLfAndCrlfEndings) {
  for (const std::string newline : {"\n", "\r\n"}) {
    std::vector<Point2> expected;
    const std::string text = lane(30000, newline, &expected);
    ASSERT_GT(text.size(), 8u * 65536u);  // many blocks
    EXPECT_EQ(read(writeFile("many_blocks.csv", text)), expected);
    // Without the last newline: the last point is still read.
    EXPECT_EQ(read(writeFile("no_last_newline.csv", text.substr(0, text.size() - newline.size()))), expected);
  }
}

TEST(PointsFile, ALineLongerThanABlockIsReadWhole) {
  // 200 KiB of blanks before the numbers: the line outgrows the 64 KiB block, which grows.
  const std::string text = "x,y\n1,2\n" + std::string(200000, ' ') + "3,4\n5,6";
  EXPECT_EQ(read(writeFile("long_line.csv", text)), (std::vector<Point2>{{1, 2}, {3, 4}, {5, 6}}));
}

TEST(PointsFile, ABadLineIsNamedByItsNumberInAnyBlock) {
  std::vector<Point2> expected;
  std::string text = lane(20000, "\n", &expected);  // a header, 20,000 points and 20 comments
  text += "1,oops\n";
  std::vector<Point2> points;
  std::string error;
  EXPECT_FALSE(readPointsCsv(writeFile("bad_late.csv", text), &points, &error));
  EXPECT_NE(error.find("bad_late.csv:20022: expected 'x,y'"), std::string::npos) << error;
  EXPECT_NE(error.find("got '1,oops'"), std::string::npos) << error;
}

TEST(PointsFile, APipeIsReadInOnePass) {
  // A FIFO cannot be read twice (no count of its lines first): its points are read all the same.
  const std::string fifo = ::testing::TempDir() + "points_fifo";
  std::remove(fifo.c_str());
  ASSERT_EQ(std::system(("mkfifo " + fifo).c_str()), 0);
  std::vector<Point2> expected;
  const std::string text = lane(5000, "\n", &expected);
  const std::string source = writeFile("fifo_source.csv", text);
  ASSERT_EQ(std::system(("cat " + source + " > " + fifo + " &").c_str()), 0);
  EXPECT_EQ(read(fifo), expected);
  std::remove(fifo.c_str());
}

}  // namespace
}  // namespace lane_keeping
