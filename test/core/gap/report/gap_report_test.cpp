// Gap report: the candidate names and report.json keys of DESIGN §5 (interfaces outside checks rely on),
// a lossless JSON round trip, non-finite numbers as null, and the Markdown report.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/stat.h>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/report/gap_report.h"
#include "lane_keeping/gap/report/gap_report_markdown.h"

namespace lane_keeping {
namespace {

using Json = nlohmann::json;

std::string tempDir(const std::string& name) {
  const std::string dir = testing::TempDir() + name;
  mkdir(dir.c_str(), 0755);
  return dir;
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

GapReport sampleReport() {
  GapReport r;
  r.logs = {"run1.csv", "run2.bag"};
  r.heldout = {"run3.csv[500:1000]"};
  r.rows_used = 5990;
  r.rows_skipped = 10;
  r.notes = {"run1.csv: skipped 10 of 6000 rows with NaN/Inf/empty cells (lines 5, 6)"};
  r.where.subsystem = "chassis";
  r.where.subsystems = {{"steering", 0.02, 0.01, {"delta", "delta_rate"}},
                        {"chassis", 0.35, 0.012, {"yaw_rate", "psi", "y", "ay"}},
                        {"tracker", 0.001, 0.0005, {"delta_des"}},
                        {"actuator", 0.004, 0.001, {"torque"}}};
  r.where.windows = {{"run.csv", 12.5, 14.0, 0.41}, {"run.csv", 3.0, 4.5, 0.2}};
  r.where.bands = {{0.0, 0.5, 0.1}, {0.5, 2.0, 0.7}, {2.0, 10.0, 0.2}};
  r.where.regimes = {{"slip_angle", 0.02, 0.05, 0.6, 0.2}, {"lateral_acceleration", 0.0, 2.0, 0.1, 0.5}};
  RankedEffect a;
  a.effect = "tire_lag";
  a.params = {{"relaxation_length", 0.62}};
  a.param_sigma = {{"relaxation_length", 0.03}};
  a.config = {{"tire.front.relaxation_length", "0.62"}, {"tire.rear.relaxation_length", "0.62"}};
  a.train_gap_before = 0.31;
  a.train_gap_after = 0.04;
  a.heldout_gap_before = 0.33;
  a.heldout_gap_after = 0.05;
  a.shrink = 1.0 - 0.05 / 0.33;
  a.score = 120.5;
  RankedEffect b;
  b.effect = "sensing_delay";
  b.params = {{"delay", 0.012}};
  b.param_sigma = {{"delay", 0.004}};
  b.config = {{"delays.sensing", "0.012"}};
  b.heldout_gap_before = 0.33;
  b.heldout_gap_after = 0.2;
  b.shrink = 1.0 - 0.2 / 0.33;
  b.score = 30;
  b.closed_loop_bounded = false;
  RankedEffect c;  // its closed loop not checked: it could not change the verdict (closed_loop_checks.h)
  c.effect = "road_friction";
  c.params = {{"scale", 0.9}};
  c.heldout_gap_before = 0.33;
  c.heldout_gap_after = 0.32;
  c.shrink = 1.0 - 0.32 / 0.33;
  c.closed_loop_checked = false;
  r.ranking = {a, c, b};
  r.verdict.effect = "tire_lag";
  r.verdict.confidence = 0.91;
  r.verdict.gap_before = 0.33;
  r.verdict.gap_after = 0.05;
  r.verdict.shrink = a.shrink;
  r.verdict.reason = "tire_lag shrinks the held-out gap by 85 %, 4x more evidence than the runner-up";
  r.verdict.confusable_with = {"sensing_delay"};
  r.verdict.basis = "modal";  // not the default, so that the round trip shows it is read back
  r.how_far.before = 0.4;
  r.how_far.after = 0.06;
  r.how_far.noise_floor = 0.03;
  r.how_far.net_before = 0.39;
  r.how_far.net_after = 0.052;
  r.how_far.subsystems_before = {{"chassis", 0.35}, {"steering", 0.02}};
  r.how_far.subsystems_after = {{"chassis", 0.05}, {"steering", 0.02}};
  r.wall_seconds = {{"where", 0.8}, {"fit tire_lag", 5.75}, {"which", 12.5}};
  return r;
}

void expectSameDouble(double a, double b, const std::string& what) {
  if (std::isnan(a)) EXPECT_TRUE(std::isnan(b)) << what;
  else EXPECT_EQ(a, b) << what;
}

void expectSame(const GapReport& a, const GapReport& b) {
  EXPECT_EQ(a.logs, b.logs);
  EXPECT_EQ(a.heldout, b.heldout);
  EXPECT_EQ(a.rows_used, b.rows_used);
  EXPECT_EQ(a.rows_skipped, b.rows_skipped);
  EXPECT_EQ(a.notes, b.notes);
  EXPECT_EQ(a.where.subsystem, b.where.subsystem);
  ASSERT_EQ(a.where.subsystems.size(), b.where.subsystems.size());
  for (std::size_t i = 0; i < a.where.subsystems.size(); ++i) {
    EXPECT_EQ(a.where.subsystems[i].name, b.where.subsystems[i].name);
    expectSameDouble(a.where.subsystems[i].nrmse, b.where.subsystems[i].nrmse, "nrmse");
    expectSameDouble(a.where.subsystems[i].noise_floor, b.where.subsystems[i].noise_floor, "noise_floor");
    EXPECT_EQ(a.where.subsystems[i].outputs, b.where.subsystems[i].outputs);
  }
  ASSERT_EQ(a.where.windows.size(), b.where.windows.size());
  for (std::size_t i = 0; i < a.where.windows.size(); ++i) {
    EXPECT_EQ(a.where.windows[i].log, b.where.windows[i].log);
    expectSameDouble(a.where.windows[i].t0, b.where.windows[i].t0, "t0");
    expectSameDouble(a.where.windows[i].t1, b.where.windows[i].t1, "t1");
    expectSameDouble(a.where.windows[i].share, b.where.windows[i].share, "share");
  }
  ASSERT_EQ(a.where.bands.size(), b.where.bands.size());
  for (std::size_t i = 0; i < a.where.bands.size(); ++i) {
    expectSameDouble(a.where.bands[i].f0, b.where.bands[i].f0, "f0");
    expectSameDouble(a.where.bands[i].f1, b.where.bands[i].f1, "f1");
    expectSameDouble(a.where.bands[i].share, b.where.bands[i].share, "share");
  }
  ASSERT_EQ(a.where.regimes.size(), b.where.regimes.size());
  for (std::size_t i = 0; i < a.where.regimes.size(); ++i) {
    EXPECT_EQ(a.where.regimes[i].variable, b.where.regimes[i].variable);
    expectSameDouble(a.where.regimes[i].lo, b.where.regimes[i].lo, "lo");
    expectSameDouble(a.where.regimes[i].hi, b.where.regimes[i].hi, "hi");
    expectSameDouble(a.where.regimes[i].share, b.where.regimes[i].share, "share");
    expectSameDouble(a.where.regimes[i].time_share, b.where.regimes[i].time_share, "time_share");
  }
  ASSERT_EQ(a.ranking.size(), b.ranking.size());
  for (std::size_t i = 0; i < a.ranking.size(); ++i) {
    const RankedEffect& x = a.ranking[i];
    const RankedEffect& y = b.ranking[i];
    EXPECT_EQ(x.effect, y.effect);
    EXPECT_EQ(x.params, y.params);
    EXPECT_EQ(x.param_sigma, y.param_sigma);
    EXPECT_EQ(x.config, y.config);
    expectSameDouble(x.train_gap_before, y.train_gap_before, "train_gap_before");
    expectSameDouble(x.train_gap_after, y.train_gap_after, "train_gap_after");
    expectSameDouble(x.heldout_gap_before, y.heldout_gap_before, "heldout_gap_before");
    expectSameDouble(x.heldout_gap_after, y.heldout_gap_after, "heldout_gap_after");
    expectSameDouble(x.shrink, y.shrink, "shrink");
    expectSameDouble(x.score, y.score, "score");
    EXPECT_EQ(x.closed_loop_bounded, y.closed_loop_bounded) << x.effect;
    EXPECT_EQ(x.closed_loop_checked, y.closed_loop_checked) << x.effect;
  }
  EXPECT_EQ(a.verdict.effect, b.verdict.effect);
  expectSameDouble(a.verdict.confidence, b.verdict.confidence, "confidence");
  expectSameDouble(a.verdict.gap_before, b.verdict.gap_before, "gap_before");
  expectSameDouble(a.verdict.gap_after, b.verdict.gap_after, "gap_after");
  expectSameDouble(a.verdict.shrink, b.verdict.shrink, "verdict shrink");
  EXPECT_EQ(a.verdict.reason, b.verdict.reason);
  EXPECT_EQ(a.verdict.basis, b.verdict.basis);
  EXPECT_EQ(a.verdict.confusable_with, b.verdict.confusable_with);
  expectSameDouble(a.how_far.before, b.how_far.before, "how_far.before");
  expectSameDouble(a.how_far.after, b.how_far.after, "how_far.after");
  expectSameDouble(a.how_far.noise_floor, b.how_far.noise_floor, "how_far.noise_floor");
  expectSameDouble(a.how_far.net_before, b.how_far.net_before, "how_far.net_before");
  expectSameDouble(a.how_far.net_after, b.how_far.net_after, "how_far.net_after");
  EXPECT_EQ(a.how_far.subsystems_before, b.how_far.subsystems_before);
  EXPECT_EQ(a.how_far.subsystems_after, b.how_far.subsystems_after);
  EXPECT_EQ(a.wall_seconds, b.wall_seconds);
}

TEST(GapReportNames, CandidateEffectsAreExactlyDesignSection5) {
  const std::vector<std::string> expected{"tire_lag",          "sensing_delay",       "actuation_delay",
                                          "steering_friction", "torque_limit",        "road_friction",
                                          "cornering_stiffness", "lateral_disturbance", "pose_bias",
                                          "steering_compliance", "inertia",
                                          // the sensor and data errors, each naming its channel as its form
                                          "sensor_offset",     "sensor_scale",        "sensor_latency"};
  EXPECT_EQ(candidateEffectNames(), expected);
}

TEST(GapReportJson, RoundTripIsLossless) {
  const GapReport report = sampleReport();
  const std::string path = tempDir("gr_roundtrip") + "/report.json";
  writeGapReportJson(path, report);
  expectSame(report, readGapReportJson(path));
}

TEST(GapReportJson, DirectoryArgumentMeansDirSlashReportJson) {
  const std::string dir = tempDir("gr_dir");
  std::remove((dir + "/report.json").c_str());
  writeGapReportJson(dir, sampleReport());
  EXPECT_FALSE(readText(dir + "/report.json").empty());
  expectSame(sampleReport(), readGapReportJson(dir));
}

TEST(GapReportJson, ContainsTheDesignSection5Keys) {
  const std::string path = tempDir("gr_keys") + "/report.json";
  writeGapReportJson(path, sampleReport());
  const Json j = Json::parse(readText(path));
  // where
  ASSERT_TRUE(j.contains("where"));
  EXPECT_EQ(j.at("where").at("subsystem"), "chassis");
  ASSERT_TRUE(j.at("where").at("subsystems").is_array());
  EXPECT_EQ(j.at("where").at("subsystems").size(), 4u);
  for (const auto& s : j.at("where").at("subsystems")) {
    EXPECT_TRUE(s.at("name").is_string());
    EXPECT_TRUE(s.at("nrmse").is_number());
  }
  EXPECT_DOUBLE_EQ(j.at("where").at("subsystems").at(1).at("nrmse").get<double>(), 0.35);
  for (const auto& w : j.at("where").at("windows"))
    for (const char* key : {"t0", "t1", "share"}) EXPECT_TRUE(w.at(key).is_number()) << key;
  EXPECT_EQ(j.at("where").at("bands").size(), 3u);
  for (const auto& b : j.at("where").at("bands"))
    for (const char* key : {"f0", "f1", "share"}) EXPECT_TRUE(b.at(key).is_number()) << key;
  // ranking
  ASSERT_TRUE(j.at("ranking").is_array());
  ASSERT_EQ(j.at("ranking").size(), 3u);
  for (const auto& e : j.at("ranking")) {
    EXPECT_TRUE(e.at("effect").is_string());
    EXPECT_TRUE(e.at("params").is_object());
    for (const char* key : {"heldout_gap_before", "heldout_gap_after", "shrink"}) EXPECT_TRUE(e.at(key).is_number()) << key;
  }
  EXPECT_EQ(j.at("ranking").at(0).at("effect"), "tire_lag");
  EXPECT_DOUBLE_EQ(j.at("ranking").at(0).at("params").at("relaxation_length").get<double>(), 0.62);
  // verdict
  EXPECT_EQ(j.at("verdict").at("effect"), "tire_lag");
  for (const char* key : {"confidence", "gap_before", "gap_after", "shrink"})
    EXPECT_TRUE(j.at("verdict").at(key).is_number()) << key;
  EXPECT_DOUBLE_EQ(j.at("verdict").at("shrink").get<double>(), 1.0 - 0.05 / 0.33);
  // the rest of GapReport
  EXPECT_EQ(j.at("rows_used"), 5990);
  EXPECT_EQ(j.at("rows_skipped"), 10);
  EXPECT_EQ(j.at("where").at("regimes").at(0).at("variable"), "slip_angle");
  EXPECT_DOUBLE_EQ(j.at("ranking").at(0).at("param_sigma").at("relaxation_length").get<double>(), 0.03);
  EXPECT_EQ(j.at("ranking").at(0).at("config").at("tire.front.relaxation_length"), "0.62");
  EXPECT_DOUBLE_EQ(j.at("how_far").at("shrink").get<double>(), 1.0 - 0.06 / 0.4);
  EXPECT_DOUBLE_EQ(j.at("how_far").at("net_shrink").get<double>(), 1.0 - 0.052 / 0.39);
  EXPECT_EQ(j.at("verdict").at("confusable_with").at(0), "sensing_delay");
}

TEST(GapReportJson, NonFiniteNumbersBecomeNull) {
  GapReport report = sampleReport();
  report.notes.clear();  // they mention "NaN" in words
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  report.verdict.effect = "unexplained";
  report.verdict.shrink = nan;
  report.verdict.gap_after = inf;
  report.ranking[2].heldout_gap_after = -inf;
  report.ranking[0].params["relaxation_length"] = nan;
  report.where.subsystems[2].nrmse = nan;
  report.how_far.before = 0.0;  // how_far.shrink undefined
  const std::string path = tempDir("gr_nan") + "/report.json";
  writeGapReportJson(path, report);
  const std::string text = readText(path);
  EXPECT_FALSE(has(text, "NaN") || has(text, "nan") || has(text, "Infinity") || has(text, "inf\"")) << text;
  const Json j = Json::parse(text);  // throws if invalid
  EXPECT_TRUE(j.at("verdict").at("shrink").is_null());
  EXPECT_TRUE(j.at("verdict").at("gap_after").is_null());
  EXPECT_TRUE(j.at("ranking").at(2).at("heldout_gap_after").is_null());
  EXPECT_TRUE(j.at("ranking").at(0).at("params").at("relaxation_length").is_null());
  EXPECT_TRUE(j.at("where").at("subsystems").at(2).at("nrmse").is_null());
  EXPECT_TRUE(j.at("how_far").at("shrink").is_null());
  const GapReport back = readGapReportJson(path);
  EXPECT_TRUE(std::isnan(back.verdict.shrink));
  EXPECT_TRUE(std::isnan(back.verdict.gap_after));  // +-Inf come back as NaN (documented)
  EXPECT_TRUE(std::isnan(back.ranking[2].heldout_gap_after));
  EXPECT_TRUE(std::isnan(back.ranking[0].params.at("relaxation_length")));
  EXPECT_EQ(back.verdict.effect, "unexplained");
}

// Found by fuzzing (fuzz/regressions/gap_report/number_overflow.json): a number beyond double's range made
// nlohmann::json throw out_of_range (not parse_error), which escaped the reader.
TEST(GapReportJson, NumberBeyondDoubleRangeIsAnInputErrorNamingTheFile) {
  const std::string path = tempDir("gr_overflow") + "/report.json";
  std::ofstream(path) << "{\"rows_used\": 2.7E89745673883776}\n";
  try {
    readGapReportJson(path);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_TRUE(has(e.what(), path + ": not valid JSON")) << e.what();
  }
}

TEST(GapReportJson, ErrorsNameFileAndKey) {
  const std::string dir = tempDir("gr_errors");
  // Unwritable target.
  try {
    writeGapReportJson(dir + "/missing_subdir/report.json", sampleReport());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_TRUE(has(e.what(), dir + "/missing_subdir/report.json")) << e.what();
  }
  // Missing file, invalid JSON, a DESIGN key missing, a wrong type.
  const auto readError = [](const std::string& path) -> std::string {
    try {
      readGapReportJson(path);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no InputError)";
  };
  EXPECT_TRUE(has(readError(dir + "/none.json"), dir + "/none.json")) << readError(dir + "/none.json");
  const std::string broken = dir + "/broken.json";
  std::ofstream(broken) << "{\"where\": {";
  EXPECT_TRUE(has(readError(broken), broken + ": not valid JSON")) << readError(broken);

  Json j = Json::parse(readText((writeGapReportJson(dir + "/ok.json", sampleReport()), dir + "/ok.json")));
  j["verdict"].erase("effect");
  const std::string no_effect = dir + "/no_effect.json";
  std::ofstream(no_effect) << j.dump();
  EXPECT_TRUE(has(readError(no_effect), no_effect + ": $.verdict.effect: missing")) << readError(no_effect);

  j = Json::parse(readText(dir + "/ok.json"));
  j["ranking"][1]["shrink"] = "large";
  const std::string bad_type = dir + "/bad_type.json";
  std::ofstream(bad_type) << j.dump();
  EXPECT_TRUE(has(readError(bad_type), "$.ranking[1].shrink: expected a number")) << readError(bad_type);

  // A report written before the checks were lazy has no closed_loop_checked: every fit was checked.
  j = Json::parse(readText(dir + "/ok.json"));
  ASSERT_EQ(j["ranking"][1]["closed_loop_checked"], false);
  j["ranking"][1].erase("closed_loop_checked");
  const std::string older = dir + "/older.json";
  std::ofstream(older) << j.dump();
  EXPECT_TRUE(readGapReportJson(older).ranking[1].closed_loop_checked);
}

TEST(GapReportMarkdown, MentionsVerdictOverlayEveryRankedEffectAndExistingPlots) {
  const std::string dir = tempDir("gr_md");
  std::remove((dir + "/overlay.png").c_str());
  std::ofstream(dir + "/residuals.png") << "png";
  const GapReport report = sampleReport();
  writeGapReportMarkdown(dir, report);
  const std::string md = readText(dir + "/report.md");
  ASSERT_FALSE(md.empty());
  EXPECT_TRUE(has(md, "## Verdict\n\n**tire_lag** (confidence 0.91)")) << md;
  EXPECT_LT(md.find("## Verdict"), md.find("## Ranking"));
  for (const RankedEffect& e : report.ranking) EXPECT_TRUE(has(md, e.effect)) << e.effect;
  EXPECT_TRUE(has(md, "relaxation_length = 0.62 ± 0.03")) << md;
  EXPECT_TRUE(has(md, "tire:\n  front:\n    relaxation_length: 0.62\n  rear:\n    relaxation_length: 0.62\n")) << md;
  EXPECT_TRUE(has(md, "--set tire.front.relaxation_length=0.62")) << md;
  EXPECT_TRUE(has(md, "confusable with: sensing_delay")) << md;
  EXPECT_TRUE(has(md, "rows skipped (NaN/Inf/empty cells): 10")) << md;
  EXPECT_TRUE(has(md, "| 12.5 | 14 | 41.0 % |")) << md;
  EXPECT_TRUE(has(md, "Closed-loop replay gap: 0.4 → 0.06 (shrink 85.0 %)")) << md;
  EXPECT_TRUE(has(md, "](residuals.png)")) << md;
  EXPECT_FALSE(has(md, "](overlay.png)")) << md;
  EXPECT_TRUE(has(md, "sensing_delay (closed loop unbounded)")) << md;
  EXPECT_TRUE(has(md, "Closed loops not checked (their boundedness could not change the verdict, or the logs cannot "
                      "drive one): road_friction.")) << md;
}

/// The fields for real logs (issue 46, 48): input checks, each log's start, and a closed loop that did not run.
GapReport realLogReport() {
  GapReport r = sampleReport();
  const double epoch = 1692000000.0;  // a log stamped in epoch time
  r.logs_t0 = {{"run.csv", epoch}, {"run2.csv", 0.25}};
  r.where.windows = {{"run.csv", epoch + 12.5, epoch + 14.0, 0.41, epoch}, {"run.csv", epoch + 3.0, epoch + 4.5, 0.2, epoch}};
  InputCheckEntry hole{"run.csv", "t", "hole", "no samples for 5 s (2500 median steps) from 6 s to 11 s after the log's start",
                       epoch + 6.0, epoch + 11.0};
  InputCheckEntry stuck;
  stuck.log = "run.csv";
  stuck.channel = "delta";
  stuck.kind = "stuck";
  stuck.detail = "delta is constant at 0 rad while delta_des implies it moves by 0.012 rad RMS";
  r.input_checks = {hole, stuck};
  r.how_far.before = r.how_far.after = std::numeric_limits<double>::quiet_NaN();
  r.how_far.not_run = "the logs cannot drive the closed loop: run.csv: the log has no delta_des";
  return r;
}

TEST(GapReportJson, RealLogFieldsRoundTrip) {
  const GapReport r = realLogReport();
  const std::string path = testing::TempDir() + "gr_real.json";
  writeGapReportJson(path, r);
  const GapReport back = readGapReportJson(path);
  expectSame(r, back);
  EXPECT_EQ(back.logs_t0, r.logs_t0);
  ASSERT_EQ(back.where.windows.size(), 2u);
  EXPECT_EQ(back.where.windows[0].log_t0, 1692000000.0);
  EXPECT_EQ(back.where.windows[0].t0, 1692000012.5);  // DESIGN §5's window stays in the log's own time
  ASSERT_EQ(back.input_checks.size(), 2u);
  EXPECT_EQ(back.input_checks[0].kind, "hole");
  EXPECT_EQ(back.input_checks[0].t1, 1692000011.0);
  EXPECT_EQ(back.input_checks[1].channel, "delta");
  EXPECT_EQ(back.input_checks[1].detail, r.input_checks[1].detail);
  EXPECT_TRUE(std::isnan(back.input_checks[1].t0));
  EXPECT_EQ(back.how_far.not_run, r.how_far.not_run);
  const Json j = Json::parse(readText(path));
  EXPECT_TRUE(j["how_far"]["before"].is_null());
  EXPECT_EQ(j["input_checks"][1].count("t0"), 0u);  // only holes carry where they are
  EXPECT_EQ(j["logs_t0"]["run.csv"].get<double>(), 1692000000.0);
}

TEST(GapReportMarkdown, TimesSinceTheLogsStartInputChecksAndAClosedLoopThatDidNotRun) {
  const std::string dir = tempDir("gr_md_real");
  writeGapReportMarkdown(dir, realLogReport());
  const std::string md = readText(dir + "/report.md");
  EXPECT_TRUE(has(md, "| run.csv | 12.5 | 14 | 41.0 % |")) << md;  // not 1.692e+09
  EXPECT_FALSE(has(md, "e+09")) << md;
  EXPECT_TRUE(has(md, "run.csv starts at t = 1692000000.000 s in its own time.")) << md;
  EXPECT_TRUE(has(md, "## Input checks\n\n- run.csv, t (hole): no samples for 5 s")) << md;
  EXPECT_TRUE(has(md, "- run.csv, delta (stuck): delta is constant at 0 rad")) << md;
  EXPECT_TRUE(has(md, "Closed-loop replay gap: not run (the logs cannot drive the closed loop: run.csv: the log has "
                      "no delta_des)"))
      << md;
  EXPECT_FALSE(has(md, "Closed-loop replay gap: n/a")) << md;
  // A report without findings says that the logs were checked.
  writeGapReportMarkdown(dir, sampleReport());
  EXPECT_TRUE(has(readText(dir + "/report.md"), "## Input checks\n\nNothing odd found in the logs")) << md;
}

TEST(GapReportMarkdown, UnexplainedVerdictAndNonFiniteNumbers) {
  GapReport report = sampleReport();
  report.verdict.effect = "unexplained";
  report.verdict.shrink = std::numeric_limits<double>::quiet_NaN();
  const std::string dir = testing::TempDir() + "gr_md_new_dir/sub";  // created by the writer
  writeGapReportMarkdown(dir, report);
  const std::string md = readText(dir + "/report.md");
  EXPECT_TRUE(has(md, "**unexplained**")) << md;
  EXPECT_TRUE(has(md, "shrink n/a")) << md;
  EXPECT_TRUE(has(md, "no config overlay is proposed")) << md;
  for (const RankedEffect& e : report.ranking) EXPECT_TRUE(has(md, e.effect)) << e.effect;
}

}  // namespace
}  // namespace lane_keeping
