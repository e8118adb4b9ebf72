// The tools' numeric options (common/command_line.h): a value is the whole text, finite, within its range,
// or a UsageError naming the option and the value. std::atoi read "--threads abc" as 0 and
// "--noise-reference-draws 5x" as 5.
#include <gtest/gtest.h>

#include <string>

#include "lane_keeping/common/command_line.h"
#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

std::string refusal(const std::string& text, bool whole = true) {
  try {
    if (whole) wholeNumberOption("--threads", text, 1, 256);
    else numberOption("--tau2-max", text, 1e-6, 10.0, "s");
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(CommandLine, WholeNumbersAreReadWholeOrRefusedNamingOptionAndValue) {
  EXPECT_EQ(wholeNumberOption("--threads", "12", 1, 256), 12);
  EXPECT_EQ(wholeNumberOption("--threads", "+3", 1, 256), 3);
  EXPECT_EQ(wholeNumberOption("--n", "1e3", 2, 1000000), 1000);
  for (const std::string bad : {"abc", "", " 5", "5 ", "5x", "2.5", "0x10", "+-5", "nan", "inf", "1e999"}) {
    const std::string message = refusal(bad);
    EXPECT_NE(message.find("--threads"), std::string::npos) << "'" << bad << "': " << message;
    EXPECT_NE(message.find("not a whole number"), std::string::npos) << "'" << bad << "': " << message;
  }
  EXPECT_EQ(refusal("abc"), "--threads: 'abc' is not a whole number (expected one in [1, 256])");
  EXPECT_EQ(refusal("0"), "--threads: 0 is out of range: must be in [1, 256]");
  EXPECT_EQ(refusal("1000000000000"), "--threads: 1000000000000 is out of range: must be in [1, 256]");
  // A control character is shown, not printed raw.
  EXPECT_NE(refusal(std::string("4\x01")).find("\\x01"), std::string::npos);
}

TEST(CommandLine, NumbersAreFiniteAndInRange) {
  EXPECT_DOUBLE_EQ(numberOption("--tau2-max", "0.05", 1e-6, 10.0, "s"), 0.05);
  EXPECT_DOUBLE_EQ(numberOption("--tau2-max", "5e-3", 1e-6, 10.0, "s"), 5e-3);
  EXPECT_EQ(refusal("nan", false), "--tau2-max: 'nan' is not a number (expected one in [1e-06, 10] s)");
  EXPECT_EQ(refusal("20", false), "--tau2-max: 20 s is out of range: must be in [1e-06, 10] s");
  EXPECT_NE(refusal("0.05s", false).find("not a number"), std::string::npos);
  EXPECT_NE(refusal("-inf", false).find("not a number"), std::string::npos);
}

}  // namespace
}  // namespace lane_keeping
