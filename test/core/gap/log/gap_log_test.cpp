// Gap-diagnosis CSV logs (DESIGN §5): column order free, optional columns, NaN rows skipped and counted,
// CRLF, and every bad input gives an InputError naming the file and, where it applies, line and column.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/sim/log_row.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

const std::string kSource = build_paths::sourceDir();

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// n rows of a valid log in the column order of `header`; row i has t = 0.01 i and col k = 0.01 (k + i)
/// (small enough for every column's plausibility limit).
std::string rowsText(const std::vector<std::string>& header, int n, int first = 0, const std::string& eol = "\n") {
  std::ostringstream out;
  for (int i = first; i < first + n; ++i) {
    for (std::size_t k = 0; k < header.size(); ++k) {
      if (k) out << ",";
      if (header[k] == "t") out << 0.01 * i;
      else out << 0.01 * (static_cast<double>(k) + i);
    }
    out << eol;
  }
  return out.str();
}

std::string headerText(const std::vector<std::string>& header, const std::string& eol = "\n") {
  std::string out;
  for (std::size_t k = 0; k < header.size(); ++k) out += (k ? "," : "") + header[k];
  return out + eol;
}

const std::vector<std::string> kRequired{"t", "x", "y", "psi", "yaw_rate", "delta", "delta_des", "torque"};

std::string errorOf(const std::string& path) {
  try {
    readCsvLog(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(GapLogRead, RequiredColumnsInAnyOrderExtraColumnsIgnored) {
  const std::vector<std::string> header{"torque", "extra", "delta_des", "t", "psi", "y", "x", "delta", "yaw_rate"};
  const std::string path = writeTemp("gl_order.csv", headerText(header) + rowsText(header, 20));
  const GapLog log = readCsvLog(path);
  ASSERT_EQ(log.size(), 20u);
  EXPECT_EQ(log.source, path);
  EXPECT_EQ(log.rows_read, 20u);
  EXPECT_EQ(log.rows_skipped, 0u);
  EXPECT_FALSE(log.hasSpeed());
  EXPECT_FALSE(log.hasLateralAcceleration());
  EXPECT_FALSE(log.hasSteeringRate());
  // Column k holds 0.01 (k + i): torque is column 0, delta_des 2, psi 4, x 6, yaw_rate 8.
  EXPECT_DOUBLE_EQ(log.torque[3], 0.03);
  EXPECT_DOUBLE_EQ(log.delta_des[3], 0.05);
  EXPECT_DOUBLE_EQ(log.psi[3], 0.07);
  EXPECT_DOUBLE_EQ(log.x[3], 0.09);
  EXPECT_DOUBLE_EQ(log.yaw_rate[3], 0.11);
  EXPECT_DOUBLE_EQ(log.t[3], 0.03);
  EXPECT_NEAR(log.medianStep(), 0.01, 1e-12);
  EXPECT_NEAR(log.duration(), 0.19, 1e-12);
}

TEST(GapLogRead, OptionalColumnsRead) {
  std::vector<std::string> header = kRequired;
  header.insert(header.end(), {"v", "ay", "delta_rate"});
  const GapLog log = readCsvLog(writeTemp("gl_optional.csv", headerText(header) + rowsText(header, 12)));
  ASSERT_TRUE(log.hasSpeed());
  ASSERT_TRUE(log.hasLateralAcceleration());
  ASSERT_TRUE(log.hasSteeringRate());
  EXPECT_EQ(log.v.size(), 12u);
  EXPECT_DOUBLE_EQ(log.v[1], 0.09);
  EXPECT_DOUBLE_EQ(log.ay[1], 0.1);
  EXPECT_DOUBLE_EQ(log.delta_rate[1], 0.11);
}

TEST(GapLogRead, CrlfWhitespaceAndBlankLines) {
  std::string text = " t , x ,y,psi,yaw_rate,delta,delta_des,torque \r\n";
  for (int i = 0; i < 15; ++i) {
    text += "  " + std::to_string(0.1 * i) + " ,1, 2 ,3,4,0.5,0.6, 7\r\n";
    if (i == 4) text += "\r\n";
  }
  const GapLog log = readCsvLog(writeTemp("gl_crlf.csv", text));
  ASSERT_EQ(log.size(), 15u);
  EXPECT_DOUBLE_EQ(log.torque.back(), 7.0);
  EXPECT_DOUBLE_EQ(log.y[0], 2.0);
  EXPECT_NEAR(log.t.back(), 1.4, 1e-12);
}

TEST(GapLogRead, NanInfAndEmptyCellsSkipRowsAndAreCounted) {
  std::vector<std::string> header = kRequired;
  header.push_back("v");
  std::string text = headerText(header) + rowsText(header, 5);                   // lines 2-6
  text += "0.05,1,2,3,nan,0.5,0.6,7,8\n";                                             // line 7: NaN yaw_rate
  text += "0.06,1,2,3,4,0.5,0.6,inf,8\n";                                             // line 8: Inf torque
  text += "0.07,1,2,3,4,0.5,,7,8\n";                                                // line 9: empty delta_des
  text += "0.08,1,2,3,4,0.5,0.6,7,NaN\n";                                             // line 10: NaN optional v
  text += rowsText(header, 10, 9);                                                // lines 11-20
  const std::string path = writeTemp("gl_nan.csv", text);
  const GapLog log = readCsvLog(path);
  EXPECT_EQ(log.rows_read, 19u);
  EXPECT_EQ(log.rows_skipped, 4u);
  EXPECT_EQ(log.size(), 15u);
  EXPECT_EQ(log.v.size(), 15u);
  for (double v : log.yaw_rate) EXPECT_TRUE(std::isfinite(v));
  ASSERT_FALSE(log.notes.empty());
  const std::string note = log.notes.back();
  EXPECT_TRUE(has(note, path)) << note;
  EXPECT_TRUE(has(note, "skipped 4")) << note;
  EXPECT_TRUE(has(note, "lines 7, 8, 9, 10")) << note;
  EXPECT_TRUE(has(note, "yaw_rate 1")) << note;
}

TEST(GapLogRead, AValueNoCarProducesIsAnErrorNamingLineColumnAndLimit) {
  // 20 rows whose torque holds 1e308 on line 12: a units error, not data to fit (lk_gap used to return
  // torque_limit removing 100 % of a gap of 1.2e9).
  std::string text = headerText(kRequired) + rowsText(kRequired, 10);  // lines 2-11
  text += "0.1,1,2,3,0.5,0.1,0.1,1e308\n";                             // line 12
  text += rowsText(kRequired, 9, 11);
  const std::string error = errorOf(writeTemp("gl_huge.csv", text));
  EXPECT_TRUE(has(error, "gl_huge.csv:12: column 'torque' holds 1e+308")) << error;
  EXPECT_TRUE(has(error, "|torque| <= 100000 N m")) << error;
  // The limits sit beyond driving, not at it: a steering-wheel angle of 1.5 rad passes as delta.
  std::string ok = headerText(kRequired) + rowsText(kRequired, 10);
  ok += "0.1,1,2,3,0.5,1.5,0.1,50\n";
  ok += rowsText(kRequired, 9, 11);
  EXPECT_EQ(readCsvLog(writeTemp("gl_ok.csv", ok)).size(), 20u);
}

TEST(GapLogRead, OptionalColumnWithoutAnyValueIsTreatedAsAbsent) {
  std::vector<std::string> header = kRequired;
  header.push_back("ay");
  std::string text = headerText(header);
  for (int i = 0; i < 12; ++i) text += std::to_string(0.01 * i) + ",1,2,3,4,0.5,0.6,7,\n";
  const GapLog log = readCsvLog(writeTemp("gl_empty_ay.csv", text));
  EXPECT_EQ(log.size(), 12u);
  EXPECT_EQ(log.rows_skipped, 0u);
  EXPECT_FALSE(log.hasLateralAcceleration());
  ASSERT_FALSE(log.notes.empty());
  EXPECT_TRUE(has(log.notes[0], "'ay'")) << log.notes[0];
}

TEST(GapLogErrors, MissingFileNamesTheFile) {
  const std::string path = testing::TempDir() + "gl_does_not_exist.csv";
  const std::string error = errorOf(path);
  EXPECT_TRUE(has(error, path)) << error;
  EXPECT_TRUE(has(error, "cannot open")) << error;
}

TEST(GapLogErrors, EmptyFileNamesTheFile) {
  for (const std::string text : {"", "\n  \r\n"}) {
    const std::string path = writeTemp("gl_empty.csv", text);
    const std::string error = errorOf(path);
    EXPECT_TRUE(has(error, path + ": empty file")) << error;
  }
}

TEST(GapLogRead, APartialLogReadsWithTheColumnsItHas) {
  // A real car's log without the desired steering angle and the torque command: read, and the
  // diagnosis replays what it can (replayUnavailable says what each subsystem lacks).
  const std::vector<std::string> header{"t", "x", "y", "psi", "yaw_rate", "delta", "speed"};
  const std::string path = writeTemp("gl_partial.csv", headerText(header) + rowsText(header, 20));
  const GapLog log = readCsvLog(path);
  EXPECT_EQ(log.size(), 20u);
  EXPECT_TRUE(log.has("delta"));
  EXPECT_FALSE(log.has("delta_des"));
  EXPECT_FALSE(log.has("torque"));
  EXPECT_TRUE(log.delta_des.empty());
}

TEST(GapLogErrors, MissingTimeColumnListedWithTheColumnsFound) {
  const std::vector<std::string> header{"time", "x", "y", "psi", "yaw_rate", "delta", "speed"};
  const std::string path = writeTemp("gl_missing.csv", headerText(header) + rowsText(header, 20));
  const std::string error = errorOf(path);
  EXPECT_TRUE(has(error, path + ":1: missing required column t")) << error;
  EXPECT_TRUE(has(error, "columns found: time, x, y, psi, yaw_rate, delta, speed")) << error;
}

TEST(GapLogErrors, UnparsableCellNamesFileLineColumnAndText) {
  std::string text = headerText(kRequired) + rowsText(kRequired, 5);
  text += "0.05,1,2,3,4,0.5,0.6,7x\n";  // line 7, torque (column 8)
  text += rowsText(kRequired, 10, 6);
  const std::string path = writeTemp("gl_parse.csv", text);
  const std::string error = errorOf(path);
  EXPECT_TRUE(has(error, path + ":7:")) << error;
  EXPECT_TRUE(has(error, "'torque' (column 8)")) << error;
  EXPECT_TRUE(has(error, "'7x'")) << error;
}

TEST(GapLogErrors, NonIncreasingTimeNamesFileLineAndBothValues) {
  std::string text = headerText(kRequired) + rowsText(kRequired, 5);  // t = 0 .. 0.04 on lines 2-6
  text += "0.04,1,2,3,4,0.5,0.6,7\n";                                       // line 7 repeats t = 0.04
  text += rowsText(kRequired, 10, 6);
  const std::string path = writeTemp("gl_time.csv", text);
  const std::string error = errorOf(path);
  EXPECT_TRUE(has(error, path + ":7:")) << error;
  EXPECT_TRUE(has(error, "column 't'")) << error;
  EXPECT_TRUE(has(error, "t = 0.040000000000000001 follows t = 0.040000000000000001 (line 6)")) << error;

  std::string backwards = headerText(kRequired) + rowsText(kRequired, 12);
  backwards += "0.05,1,2,3,4,0.5,0.6,7\n";  // line 14, after t = 0.11
  const std::string path2 = writeTemp("gl_time2.csv", backwards);
  const std::string error2 = errorOf(path2);
  EXPECT_TRUE(has(error2, path2 + ":14:")) << error2;
  EXPECT_TRUE(has(error2, "(line 13)")) << error2;
}

TEST(GapLogErrors, TooFewValidRows) {
  std::string text = headerText(kRequired) + rowsText(kRequired, 8);
  text += "0.08,nan,2,3,4,0.5,0.6,7\n0.09,1,2,3,4,0.5,0.6,nan\n";
  const std::string path = writeTemp("gl_few.csv", text);
  const std::string error = errorOf(path);
  EXPECT_TRUE(has(error, path + ": only 8 valid data rows (10 read, 2 skipped")) << error;
  EXPECT_TRUE(has(error, "at least 10")) << error;
  // Header only.
  const std::string header_only = writeTemp("gl_header_only.csv", headerText(kRequired));
  EXPECT_TRUE(has(errorOf(header_only), header_only + ": only 0 valid data rows")) << errorOf(header_only);
}

TEST(GapLogErrors, RaggedRowAndDuplicateColumn) {
  std::string text = headerText(kRequired) + rowsText(kRequired, 3) + "0.03,1,2,3\n" + rowsText(kRequired, 10, 4);
  const std::string path = writeTemp("gl_ragged.csv", text);
  EXPECT_TRUE(has(errorOf(path), path + ":5: row has 4 cells")) << errorOf(path);

  std::vector<std::string> header = kRequired;
  header.push_back("x");
  const std::string dup = writeTemp("gl_dup.csv", headerText(header) + rowsText(header, 12));
  EXPECT_TRUE(has(errorOf(dup), dup + ":1: column 'x' appears twice (columns 2 and 9)")) << errorOf(dup);
}

TEST(GapLogWrite, RoundTripIsExact) {
  GapLog log;
  log.source = "memory";
  for (int i = 0; i < 30; ++i) {
    const double t = 0.1 * i + 1e-9 * i * i;
    log.t.push_back(t);
    log.x.push_back(std::sin(t) * 1e3);
    log.y.push_back(std::cos(t) / 3.0);
    log.psi.push_back(t / 7.0);
    log.yaw_rate.push_back(-t / 11.0);
    log.delta.push_back(1e-7 * t);
    log.delta_des.push_back(std::exp(-t));
    log.torque.push_back(M_PI * t);
    log.v.push_back(20.0 + t / 13.0);
    log.delta_rate.push_back(t * t);
  }
  const std::string path = testing::TempDir() + "gl_roundtrip.csv";
  writeCsvLog(path, log);
  const GapLog back = readCsvLog(path);
  EXPECT_EQ(back.t, log.t);
  EXPECT_EQ(back.x, log.x);
  EXPECT_EQ(back.y, log.y);
  EXPECT_EQ(back.psi, log.psi);
  EXPECT_EQ(back.yaw_rate, log.yaw_rate);
  EXPECT_EQ(back.delta, log.delta);
  EXPECT_EQ(back.delta_des, log.delta_des);
  EXPECT_EQ(back.torque, log.torque);
  EXPECT_EQ(back.v, log.v);
  EXPECT_EQ(back.delta_rate, log.delta_rate);
  EXPECT_FALSE(back.hasLateralAcceleration());

  GapLog bad = log;
  bad.torque.pop_back();
  try {
    writeCsvLog(path, bad);
    ADD_FAILURE() << "no error for a short column";
  } catch (const InputError& e) {
    EXPECT_TRUE(has(e.what(), "'torque' has 29 values, t has 30")) << e.what();
  }
  EXPECT_THROW(writeCsvLog(testing::TempDir() + "no_such_dir/x.csv", log), InputError);
}

TEST(GapLogSimulator, LkSimulateOutputReadsBackWithAllOptionalColumns) {
  const std::string out = testing::TempDir() + "gl_sim.csv";
  const std::string command = std::string(build_paths::lkSimulateBinary()) + " --config " + kSource +
                              "/config/scenarios/fig6.yaml --set simulation.duration=2 --out " + out +
                              " >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const GapLog log = readCsvLog(out);
  EXPECT_GE(log.size(), 10u);
  EXPECT_EQ(log.rows_skipped, 0u);
  EXPECT_TRUE(log.hasSpeed());
  EXPECT_TRUE(log.hasLateralAcceleration());
  EXPECT_TRUE(log.hasSteeringRate());
  EXPECT_NEAR(log.t.back() - log.t.front(), 2.0, 2.0 * log.medianStep() + 1e-9);
  for (std::size_t i = 1; i < log.size(); ++i) ASSERT_GT(log.t[i], log.t[i - 1]);
  for (double v : log.v) EXPECT_GT(v, 0.0);
}

TEST(GapLogFromRows, MapsStateFieldsToColumns) {
  std::vector<LogRow> rows(3);
  for (int i = 0; i < 3; ++i) {
    LogRow& r = rows[i];
    r.t = 0.5 * i;
    r.state.x = 1 + i;
    r.state.y = 2 + i;
    r.state.psi = 3 + i;
    r.state.sigma1 = 99;  // lateral velocity: not a log column
    r.state.sigma2 = 4 + i;
    r.state.speed = 5 + i;
    r.state.lateral_acceleration = 6 + i;
    r.state.delta = 7 + i;
    r.state.sigma3 = 8 + i;
    r.delta_des = 9 + i;
    r.torque_command = 10 + i;  // the `torque` column is the command M_S
    r.state.torque = -1;        // the torque acting on the wheel: not that column
  }
  rows[1].state.sigma3 = std::numeric_limits<double>::quiet_NaN();
  const GapLog log = gapLogFromRows(rows, "sim");
  EXPECT_EQ(log.source, "sim");
  EXPECT_EQ(log.rows_read, 3u);
  EXPECT_EQ(log.rows_skipped, 1u);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log.t, (std::vector<double>{0.0, 1.0}));
  EXPECT_DOUBLE_EQ(log.x[1], 3);
  EXPECT_DOUBLE_EQ(log.y[1], 4);
  EXPECT_DOUBLE_EQ(log.psi[1], 5);
  EXPECT_DOUBLE_EQ(log.yaw_rate[1], 6);
  EXPECT_DOUBLE_EQ(log.v[1], 7);
  EXPECT_DOUBLE_EQ(log.ay[1], 8);
  EXPECT_DOUBLE_EQ(log.delta[1], 9);
  EXPECT_DOUBLE_EQ(log.delta_rate[1], 10);
  EXPECT_DOUBLE_EQ(log.delta_des[1], 11);
  EXPECT_DOUBLE_EQ(log.torque[1], 12);
}

TEST(GapLogSlice, RowsAndMedianStep) {
  GapLog log;
  log.source = "f.csv";
  const std::vector<double> t{0.0, 0.1, 0.3, 0.4, 0.5, 0.9};
  log.t = t;
  for (auto* col : {&log.x, &log.y, &log.psi, &log.yaw_rate, &log.delta, &log.delta_des, &log.torque, &log.v})
    *col = std::vector<double>{1, 2, 3, 4, 5, 6};
  log.rows_skipped = 3;
  EXPECT_NEAR(log.medianStep(), 0.1, 1e-12);  // steps 0.1 0.2 0.1 0.1 0.4
  const GapLog part = log.slice(2, 5);
  EXPECT_EQ(part.t, (std::vector<double>{0.3, 0.4, 0.5}));
  EXPECT_EQ(part.torque, (std::vector<double>{3, 4, 5}));
  EXPECT_EQ(part.v, (std::vector<double>{3, 4, 5}));
  EXPECT_TRUE(part.ay.empty());
  EXPECT_EQ(part.rows_read, 3u);
  EXPECT_EQ(part.rows_skipped, 0u);
  EXPECT_EQ(part.source, "f.csv[2:5]");
  EXPECT_THROW(log.slice(4, 7), std::out_of_range);
  EXPECT_EQ(GapLog{}.medianStep(), 0.0);
  GapLog even = log.slice(0, 5);  // steps 0.1 0.2 0.1 0.1 -> median 0.1
  EXPECT_NEAR(even.medianStep(), 0.1, 1e-12);
}

}  // namespace
}  // namespace lane_keeping
