// A log handed over as a table (a pandas DataFrame through the Python module): gapLogFromTable applies the CSV
// reader's rules after parsing, so a table holding a file's numbers gives the log that file gives, and its
// errors name the table, the row and the column.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {
namespace {

const std::vector<std::string> kColumns{"t", "x", "y", "psi", "yaw_rate", "delta", "delta_des", "torque", "ay", "extra"};

/// 20 rows: column k of row i is 0.01 (k + i) (t = 0.01 i), row 7's ay NaN.
LogTable table() {
  LogTable out;
  out.source = "DataFrame logs[0]";
  out.columns = kColumns;
  out.values.assign(kColumns.size(), std::vector<double>(20));
  for (std::size_t k = 0; k < kColumns.size(); ++k) {
    for (int i = 0; i < 20; ++i) out.values[k][i] = kColumns[k] == "t" ? 0.01 * i : 0.01 * (static_cast<double>(k) + i);
  }
  out.values[8][7] = std::numeric_limits<double>::quiet_NaN();
  return out;
}

std::string writeCsv(const LogTable& t) {
  const std::string path = testing::TempDir() + "log_table.csv";
  std::ofstream out(path);
  for (std::size_t k = 0; k < t.columns.size(); ++k) out << (k ? "," : "") << t.columns[k];
  out << "\n";
  char buffer[40];
  for (std::size_t i = 0; i < t.values[0].size(); ++i) {
    for (std::size_t k = 0; k < t.columns.size(); ++k) {
      std::snprintf(buffer, sizeof(buffer), "%.17g", t.values[k][i]);
      out << (k ? "," : "") << buffer;
    }
    out << "\n";
  }
  return path;
}

TEST(LogTable, ATableGivesTheLogOfTheSameNumbersInAFile) {
  const LogTable t = table();
  const GapLog from_file = readCsvLog(writeCsv(t));
  const GapLog from_table = gapLogFromTable(t);
  EXPECT_EQ(from_table.t, from_file.t);
  EXPECT_EQ(from_table.x, from_file.x);
  EXPECT_EQ(from_table.torque, from_file.torque);
  EXPECT_EQ(from_table.ay, from_file.ay);
  EXPECT_TRUE(from_table.v.empty() && from_file.v.empty());
  ASSERT_EQ(from_table.size(), 19u);  // row 7 skipped for its NaN
  EXPECT_EQ(from_table.rows_read, 20u);
  EXPECT_EQ(from_table.rows_skipped, 1u);
  EXPECT_EQ(from_table.source, "DataFrame logs[0]");
  ASSERT_EQ(from_table.notes.size(), 1u);
  EXPECT_NE(from_table.notes[0].find("skipped 1 of 20 rows with NaN/Inf/empty cells (rows 7;"), std::string::npos)
      << from_table.notes[0];
}

TEST(LogTable, ErrorsNameTheTableTheRowAndTheColumn) {
  auto error = [](const LogTable& t, const LogMapping& m = {}) -> std::string {
    try {
      gapLogFromTable(t, m);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no InputError)";
  };
  LogTable t = table();
  t.values[0][5] = t.values[0][3];
  EXPECT_EQ(error(t).rfind("DataFrame logs[0] row 5: column 't': time not strictly increasing: t = 0.029999999999999999 "
                           "follows t = 0.040000000000000001 (row 4)", 0), 0u) << error(t);
  t = table();
  t.values[5][2] = 3.0;  // delta of 3 rad: no car steers that far
  EXPECT_NE(error(t).find("DataFrame logs[0] row 2: column 'delta' holds 3, beyond what a car produces"),
            std::string::npos) << error(t);
  t = table();
  t.columns[0] = "time";
  EXPECT_NE(error(t).find("DataFrame logs[0]: missing required column t; columns found: time, x,"), std::string::npos)
      << error(t);
  t = table();
  t.values[3].resize(5);
  EXPECT_NE(error(t).find("column 'psi' has 5 values, column 't' has 20"), std::string::npos) << error(t);
  t = table();
  LogMapping mapping;
  mapping.source = "car.yaml";
  ColumnMapping torque;
  torque.column = "eps_torque";
  torque.location = "car.yaml:4";
  mapping.columns["torque"] = torque;
  EXPECT_NE(error(t, mapping).find("column 'eps_torque' (mapped to torque by car.yaml:4) is not in the table"),
            std::string::npos) << error(t, mapping);
}

}  // namespace
}  // namespace lane_keeping
