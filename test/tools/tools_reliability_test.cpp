// The tools as a user runs them, on the bad arguments and inputs of issue 48 (docs/reliability.md): each is
// refused before any work with exit status 2 (arguments, configuration) or 4 (input data) and a message
// naming the option or file, where it used to be read as another value, run without bound, overwrite an
// input, lose a report or run a shell command.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "lane_keeping/common/child_process.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kSource = build_paths::sourceDir();
/// The tools under test: this build's, or another folder's (LK_TOOLS_UNDER_TEST=DIR: e.g. an older build, to
/// see these tests fail on the code before the fixes).
const std::string kBin =
    std::getenv("LK_TOOLS_UNDER_TEST") ? std::getenv("LK_TOOLS_UNDER_TEST") : build_paths::toolsDir();
const std::string kConfig = kSource + "/config/default.yaml";

ChildResult tool(const std::string& name, const std::vector<std::string>& args) {
  std::vector<std::string> argv{kBin + "/" + name};
  argv.insert(argv.end(), args.begin(), args.end());
  return runChild(argv, true);
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

#define EXPECT_REFUSED(result, status, words)                                                         \
  do {                                                                                                \
    const ChildResult& r_ = (result);                                                                 \
    EXPECT_EQ(r_.exit_status, status) << r_.error_output;                                             \
    EXPECT_NE(r_.error_output.find(words), std::string::npos) << "expected '" << (words) << "' in:\n" \
                                                              << r_.error_output;                     \
  } while (0)

/// A short simulated log (the default lane, `seconds` long, 200 Hz) with the given settings.
std::string simulatedLog(const fs::path& dir, const std::string& name, double seconds,
                         const std::vector<std::string>& sets = {}) {
  const std::string out = (dir / name).string();
  std::vector<std::string> args{"--config", kConfig, "--set", "simulation.duration=" + std::to_string(seconds),
                                "--set", "simulation.log_rate=200", "--out", out, "--quiet"};
  for (const auto& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  const ChildResult r = tool("lk_simulate", args);
  EXPECT_TRUE(r.ok()) << r.failure();
  return out;
}

// ---- strict numeric options ------------------------------------------------------------------------

TEST(ToolOptions, NumbersAreReadWholeOrRefusedWithStatus2) {
  const fs::path dir = freshDir("lk_tools_options");
  const std::string log = (dir / "none.csv").string();
  const std::vector<std::string> gap{"--config", kConfig, "--log", log, "--report", (dir / "rep").string()};
  auto with = [&](std::vector<std::string> base, const std::vector<std::string>& more) {
    base.insert(base.end(), more.begin(), more.end());
    return base;
  };
  EXPECT_REFUSED(tool("lk_gap", with(gap, {"--threads", "abc"})), 2, "--threads: 'abc' is not a whole number");
  EXPECT_REFUSED(tool("lk_gap", with(gap, {"--noise-reference-draws", "abc"})), 2,
                 "--noise-reference-draws: 'abc' is not a whole number");
  EXPECT_REFUSED(tool("lk_gap", with(gap, {"--coarse-fit-stride", "3x"})), 2, "--coarse-fit-stride: '3x'");
  EXPECT_REFUSED(tool("lk_stability", {"roots", "--config", kConfig, "--degree", "abc"}), 2,
                 "--degree: 'abc' is not a whole number");
  EXPECT_REFUSED(tool("lk_gap_benchmark", {"score", "--dir", dir.string(), "--threads", "abc"}), 2,
                 "--threads: 'abc' is not a whole number");
  EXPECT_REFUSED(tool("lk_gap_benchmark", {"generate", "--out", dir.string(), "--log-rate", "fast"}), 2,
                 "--log-rate: 'fast' is not a number");
  EXPECT_REFUSED(tool("lk_gap_benchmark", {"generate", "--out", dir.string(), "--threads"}), 2, "--threads needs a value");
  EXPECT_REFUSED(tool("lk_gap_benchmark", {"generate", "--out", dir.string(), "--family", "mine"}), 2,
                 "benchmark family 'mine' is unknown");
  EXPECT_REFUSED(tool("lk_gap_benchmark", {"score", "--dir", (dir / "none").string()}), 4, "cannot open");
  EXPECT_REFUSED(tool("lk_gap_benchmark", {"generate", "--out", dir.string(), "--noise-seed", "-3"}), 2,
                 "--noise-seed: -3 is out of range");
}

// `generate --noise-seed K`: the same case with its noise drawn afresh (its seed + K), the rest as written: a
// family's verdicts measured again on logs whose noise no rule was written after.
TEST(ToolOptions, ANoiseSeedDrawsTheSameCasesNoiseAfresh) {
  const fs::path dir = freshDir("lk_tools_noise_seed");
  const std::string id = "none-1-straight-p500-100Hz";
  for (const std::string k : {"0", "7"}) {
    const ChildResult r = tool("lk_gap_benchmark", {"generate", "--out", (dir / k).string(), "--family", "independent",
                                                    "--cases", id, "--noise-seed", k});
    ASSERT_TRUE(r.ok()) << r.error_output;
  }
  const std::string a = read(dir / "0" / "logs" / (id + ".csv")), b = read(dir / "7" / "logs" / (id + ".csv"));
  ASSERT_FALSE(a.empty());
  EXPECT_NE(a, b);
  EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), std::count(b.begin(), b.end(), '\n'));  // the same rows
  const std::string t0 = read(dir / "0" / "truth.json"), t7 = read(dir / "7" / "truth.json");
  const auto seed = [](const std::string& truth) {
    const std::size_t at = truth.find("\"seed\": ");
    return at == std::string::npos ? -1L : std::stol(truth.substr(at + 8));
  };
  EXPECT_EQ(seed(t7) - seed(t0), 7);
  EXPECT_EQ(read(dir / "0" / "cases.json"), read(dir / "7" / "cases.json"));
}

TEST(ToolOptions, TooFewNoiseDrawsAreRefusedNamingTheMinimum) {
  // 1-18 draws: the smallest p-value 1/(B+1) is above 5 %, so every gap was "nothing to explain".
  const fs::path dir = freshDir("lk_tools_draws");
  const std::vector<std::string> gap{"--config", kConfig, "--log", (dir / "none.csv").string(), "--report",
                                     (dir / "rep").string(), "--noise-reference-draws"};
  for (const std::string draws : {"1", "5", "18"}) {
    std::vector<std::string> args = gap;
    args.push_back(draws);
    EXPECT_REFUSED(tool("lk_gap", args), 2, "give at least 19 (ceil(1 / level) - 1), or 0 to turn the test off");
  }
}

// ---- lk_gap: files ---------------------------------------------------------------------------------

TEST(LkGapFiles, AHeldOutLogThatIsTheTrainingLogIsRefused) {
  const fs::path dir = freshDir("lk_tools_holdout");
  const std::string log = (dir / "run.csv").string();
  std::ofstream(log) << "t,x\n";
  fs::create_symlink(log, dir / "alias.csv");
  for (const std::string holdout : {log, (dir / "alias.csv").string(), (dir / "." / "run.csv").string()}) {
    EXPECT_REFUSED(tool("lk_gap", {"--config", kConfig, "--log", log, "--holdout", holdout, "--report",
                                   (dir / "rep").string()}),
                   2, "its held-out scores would be in-sample");
  }
}

TEST(LkGapFiles, AReportDirectoryHoldingAnInputOrOtherFilesIsRefused) {
  const fs::path dir = freshDir("lk_tools_report_inputs");
  const std::string log = (dir / "run.csv").string();
  std::ofstream(log) << "t,x\n";
  EXPECT_REFUSED(tool("lk_gap", {"--config", kConfig, "--log", log, "--report", dir.string()}), 2,
                 "holds --log " + log);
  fs::create_directories(dir / "notes");
  std::ofstream(dir / "notes" / "todo.txt") << "keep";
  EXPECT_REFUSED(tool("lk_gap", {"--config", kConfig, "--log", log, "--report", (dir / "notes").string()}), 2,
                 "holds 'todo.txt', which is not part of a gap report");
  EXPECT_EQ(read(dir / "notes" / "todo.txt"), "keep");
}

TEST(LkGapFiles, AnUnwritableReportDirectoryIsFoundBeforeTheDiagnosis) {
  const fs::path dir = freshDir("lk_tools_unwritable");
  const std::string log = simulatedLog(dir, "run.csv", 20.0);
  std::ofstream(dir / "a_file") << "x";
  const auto start = Clock::now();
  EXPECT_REFUSED(tool("lk_gap", {"--config", kConfig, "--log", log, "--report", (dir / "a_file" / "rep").string()}), 4,
                 "--report " + (dir / "a_file" / "rep").string() + ": cannot create");
  EXPECT_LT(secondsSince(start), 5.0);  // not after the diagnosis
  // A previous report that cannot be replaced (root writes anywhere, but not into an immutable directory):
  // found after the whole diagnosis before.
  const fs::path previous = dir / "previous";
  fs::create_directories(previous);
  std::ofstream(previous / "report.json") << "{}";
  if (!runChild({"/usr/bin/chattr", "+i", previous.string()}).ok()) GTEST_SKIP() << "no chattr +i here";
  const auto again = Clock::now();
  EXPECT_REFUSED(tool("lk_gap", {"--config", kConfig, "--log", log, "--report", previous.string()}), 4,
                 "the report could not replace the previous one");
  EXPECT_LT(secondsSince(again), 5.0);
  runChild({"/usr/bin/chattr", "-i", previous.string()});
}

TEST(LkGapFiles, AQuoteInTheReportDirectoryRunsNothingAndThePlotsAreDrawn) {
  // Pasted into a shell command, "x';touch F;'" ran `touch F`, and a name with a quote broke the plotting.
  const fs::path dir = freshDir("lk_tools_quote");
  const std::string log = simulatedLog(dir, "run.csv", 8.0, {"steering.coulomb_friction=2"});
  const fs::path witness = dir / "F";
  const fs::path report = dir / ("x';touch " + witness.string() + ";' O'Brien runs");
  const ChildResult r = tool("lk_gap", {"--config", kConfig, "--log", log, "--report", report.string(), "--effects",
                                        "steering_friction", "--noise-reference-draws", "0", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.failure();
  EXPECT_FALSE(fs::exists(witness));
  EXPECT_TRUE(fs::exists(report / "report.json"));
  EXPECT_TRUE(fs::exists(report / "report.md"));
  if (runChild({"/usr/bin/python3", "-c", "import matplotlib"}).ok()) {
    EXPECT_TRUE(fs::exists(report / "residuals.png")) << r.error_output;
    EXPECT_EQ(r.error_output.find("plotting failed"), std::string::npos) << r.error_output;
  }
  EXPECT_NE(read(report / "report.md").find("no detection test ran"), std::string::npos);  // 0 draws: said
}

TEST(LkGapFiles, TwoRunsIntoOneDirectoryDoNotBothSucceed) {
  const fs::path dir = freshDir("lk_tools_two_writers");
  const std::string log = simulatedLog(dir, "run.csv", 8.0, {"steering.coulomb_friction=2"});
  const std::string report = (dir / "rep").string();
  const std::vector<std::string> args{"--config", kConfig, "--log", log, "--report", report, "--effects",
                                      "steering_friction", "--noise-reference-draws", "0", "--no-plots", "--quiet"};
  ChildResult first;
  std::thread running([&] { first = tool("lk_gap", args); });
  // The second starts while the first diagnoses (it holds the lock from its start).
  const auto start = Clock::now();
  while (!fs::exists(dir / ".rep.lock") && secondsSince(start) < 20.0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const ChildResult second = tool("lk_gap", args);
  running.join();
  EXPECT_TRUE(first.ok()) << first.failure();
  EXPECT_REFUSED(second, 2, "another run is writing a report there");
  EXPECT_TRUE(fs::exists(fs::path(report) / "report.json"));
  EXPECT_TRUE(fs::exists(fs::path(report) / "report.md"));
}

TEST(LkGapFiles, ALogBeyondTheTimeBudgetIsRefusedWithAnEstimate) {
  // Time in ms read as seconds: 40 s at 100 Hz spans 39,990 "s"; the noise-only draws would simulate
  // each of them at the plant's 0.1 ms step.
  const fs::path dir = freshDir("lk_tools_budget");
  const std::string ms = (dir / "run_ms.csv").string();
  {
    std::ofstream out(ms);
    out << "t,x,y,psi,yaw_rate,delta,delta_des,torque\n";
    for (int i = 0; i < 4000; ++i) out << 10 * i << "," << 0.15 * i << ",1,0,0,0,0,0\n";
  }
  const auto start = Clock::now();
  EXPECT_REFUSED(tool("lk_gap", {"--config", kConfig, "--log", ms, "--report", (dir / "rep").string()}), 4,
                 ms + ": 4000 rows over 3.999e+04 s (a sample every 10 s): the diagnosis would take about");
  EXPECT_REFUSED(tool("lk_gap", {"--config", kConfig, "--log", ms, "--report", (dir / "rep").string()}), 4,
                 "more than --time-budget 1 h; a sample every 10 s is slower than a car's log");
  EXPECT_LT(secondsSince(start), 10.0);
  EXPECT_FALSE(fs::exists(dir / "rep"));
}

TEST(LkGapFiles, TheTimeEstimateCountsEveryRunHeldOutInTurn) {
  // Three runs: each held out in turn, a diagnosis of nearly all the data apiece (fold_pooling.h), three
  // times the estimate of the split as made (--one-fold). The same time-in-ms logs as above, refused both
  // ways, so nothing runs.
  const fs::path dir = freshDir("lk_tools_budget_folds");
  std::vector<std::string> logs;
  for (const std::string name : {"a", "b", "c"}) {
    logs.push_back((dir / (name + ".csv")).string());
    std::ofstream out(logs.back());
    out << "t,x,y,psi,yaw_rate,delta,delta_des,torque\n";
    for (int i = 0; i < 4000; ++i) out << 10 * i << "," << 0.15 * i << ",1,0,0,0,0,0\n";
  }
  std::vector<std::string> args{"--config", kConfig, "--report", (dir / "rep").string()};
  for (const std::string& log : logs) args.insert(args.end(), {"--log", log});
  const ChildResult three = tool("lk_gap", args);
  args.push_back("--one-fold");
  const ChildResult one = tool("lk_gap", args);
  EXPECT_REFUSED(three, 4, "(each of the 3 runs held out in turn)");
  EXPECT_REFUSED(one, 4, "the diagnosis would take about");
  EXPECT_EQ(one.error_output.find("held out in turn"), std::string::npos) << one.error_output;
  // "about 16 h 15 min" against "about 5 h 25 min": minutes from the "H h M min" form.
  auto minutes = [](const std::string& text) {
    const std::size_t at = text.find("would take about ");
    int h = -1, m = -1;
    if (at != std::string::npos) std::sscanf(text.c_str() + at, "would take about %d h %d min", &h, &m);
    return 60.0 * h + m;
  };
  ASSERT_GT(minutes(one.error_output), 60.0) << one.error_output;
  EXPECT_NEAR(minutes(three.error_output) / minutes(one.error_output), 3.0, 0.02);
  EXPECT_FALSE(fs::exists(dir / "rep"));
}

// ---- lk_simulate -----------------------------------------------------------------------------------

TEST(LkSimulate, AnOutputThatIsTheConfigurationIsRefused) {
  const fs::path dir = freshDir("lk_tools_simulate_out");
  const std::string config = (dir / "my.yaml").string();
  std::ofstream(config) << "simulation:\n  duration: 1\n";
  fs::create_symlink(config, dir / "alias.yaml");
  for (const std::string out : {config, (dir / "alias.yaml").string()}) {
    EXPECT_REFUSED(tool("lk_simulate", {"--config", config, "--out", out}), 2, "is the file given as --config " + config);
  }
  EXPECT_EQ(read(config), "simulation:\n  duration: 1\n");
  // The configuration lk_simulate writes beside the log (OUT.config.yaml), too.
  std::ofstream((dir / "run.csv.config.yaml").string()) << "simulation:\n  duration: 1\n";
  EXPECT_REFUSED(tool("lk_simulate", {"--config", (dir / "run.csv.config.yaml").string(), "--out", (dir / "run.csv").string()}),
                 2, "is the file given as --config");
}

TEST(LkSimulate, AScheduleTheDelaysCannotAdvanceAndBadChangesExitWith2) {
  EXPECT_REFUSED(tool("lk_simulate", {"--config", kConfig, "--set", "delays.steering_angle_to_actuator=0"}), 2,
                 "lockstep schedule cannot advance");
  EXPECT_REFUSED(tool("lk_simulate", {"--config", kConfig, "--change", "100:steering.coulomb_friction=3"}), 2,
                 "is after the run's end (simulation.duration = 10 s)");
  EXPECT_REFUSED(tool("lk_simulate", {"--config", kConfig, "--change", "5:steering.coulomb_friction=1", "--change",
                                      "5:steering.coulomb_friction=2"}),
                 2, "is changed twice at t = 5 s");
  EXPECT_REFUSED(tool("lk_simulate", {"--config", kConfig, "--set", "simulation.log_rate=20000"}), 2,
                 "is above the plant's rate");
  EXPECT_REFUSED(tool("lk_simulate", {"--config", (fs::path(kSource) / "config").string()}), 2, "is a directory");
}

// ---- lk_stability ----------------------------------------------------------------------------------

TEST(LkStability, SizesBeyondTheMachineOrTheBudgetAreRefusedNamingTheOption) {
  auto refused = [](const std::vector<std::string>& args, const std::string& words) {
    const auto start = Clock::now();
    std::vector<std::string> all{args.front(), "--config", kConfig, "--no-plot"};
    all.insert(all.end(), args.begin() + 1, args.end());
    EXPECT_REFUSED(tool("lk_stability", all), 2, words);
    EXPECT_LT(secondsSince(start), 10.0) << args.front();
  };
  const std::string out = (freshDir("lk_tools_stability") / "c").string();
  refused({"roots", "--degree", "100000"}, "--degree: 1 spectrum of order 4");
  refused({"roots", "--degree", "1500", "--time-budget", "0.01"}, "more than --time-budget 0.01 h");
  refused({"fig3", "--n", "1000000", "--out", out}, "--n and --degree: ");
  refused({"chart", "--x", "tracker.k_psi:0:2:100000", "--y", "tracker.k_y:0:0.3:100000", "--out", out},
          "--x, --y N and --degree: 1e+10 spectra");
  refused({"boundary", "--param", "tracker.k_y", "--from", "0.1", "--to", "0.1"}, "--from and --to are both");
  const ChildResult r = tool("lk_stability", {"boundary", "--config", kConfig, "--param", "tracker.k_y", "--from", "0.1",
                                              "--to", "0.1"});
  EXPECT_EQ(r.error_output.find("findFirstCrossing"), std::string::npos) << r.error_output;
}

}  // namespace
}  // namespace lane_keeping
