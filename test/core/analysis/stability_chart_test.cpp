// Stability charts (analysis/stability_chart.h): agreement with boundary searches, independence of
// the discretisation degree and of the thread count, LuGre against brush, bad axes; and the
// lk_stability tool's JSON and error handling.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lane_keeping/analysis/stability_boundary.h"
#include "lane_keeping/analysis/stability_chart.h"
#include "lane_keeping/common/errors.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

SimConfig fig6(const std::string& tire = "brush") {
  return loadSimConfig({scenario("fig6.yaml")}, {"tire.front.model=" + tire, "tire.rear.model=" + tire});
}

int stableCount(const StabilityChart& chart) {
  int n = 0;
  for (const auto& p : chart.points) n += p.stable() ? 1 : 0;
  return n;
}

TEST(StabilityChart, BoundaryLiesBetweenStableAndUnstableGridPoints) {
  const SimConfig c = fig6();
  const ChartAxis x = ChartAxis::linear("tracker.k_psi", 0.3, 1.3, 6);
  const ChartAxis y = ChartAxis::linear("tracker.k_y", 0.005, 0.205, 21);
  const StabilityChart chart = computeStabilityChart(c, x, y);
  for (std::size_t i = 0; i < x.values.size(); ++i) {
    // Going up in k_y at fixed k_psi: last stable and first unstable grid point.
    std::size_t j = 0;
    while (j < y.values.size() && chart.at(i, j).stable()) ++j;
    ASSERT_GT(j, 0u) << "k_psi = " << x.values[i] << " unstable at the smallest k_y";
    ASSERT_LT(j, y.values.size());
    SimConfig at = c;
    at.tracker.k_psi = x.values[i];
    const Crossing b = refineCrossing(configFamily(at, "tracker.k_y"), y.values[j - 1], y.values[j], SpectrumOptions{});
    EXPECT_GT(b.parameter, y.values[j - 1]);
    EXPECT_LT(b.parameter, y.values[j]);
    // The contour field interpolates the crossing mode: its zero lies within 2 % of the grid step of it.
    const double f0 = chart.at(i, j - 1).contour_field, f1 = chart.at(i, j).contour_field;
    const double interpolated = y.values[j - 1] + (y.values[j] - y.values[j - 1]) * f0 / (f0 - f1);
    EXPECT_NEAR(interpolated, b.parameter, 0.02 * (y.values[1] - y.values[0])) << "k_psi = " << x.values[i];
  }
}

TEST(StabilityChart, ClassificationDoesNotDependOnDegreeOrThreads) {
  const SimConfig c = fig6();
  const ChartAxis x = ChartAxis::linear("tracker.k_psi", 0.0, 2.5, 12);
  const ChartAxis y = ChartAxis::linear("tracker.k_y", 0.0, 0.3, 10);
  ChartOptions coarse, fine, single;
  coarse.spectrum.degree = 12;
  fine.spectrum.degree = 40;
  single.threads = 1;
  const StabilityChart a = computeStabilityChart(c, x, y, coarse);
  const StabilityChart b = computeStabilityChart(c, x, y, fine);
  const StabilityChart d = computeStabilityChart(c, x, y);
  const StabilityChart e = computeStabilityChart(c, x, y, single);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t k = 0; k < a.points.size(); ++k) {
    EXPECT_EQ(a.points[k].stable(), b.points[k].stable()) << a.points[k].x << ", " << a.points[k].y;
    EXPECT_NEAR(a.points[k].abscissa, b.points[k].abscissa, 1e-8 * (1 + std::fabs(b.points[k].abscissa)));
    EXPECT_EQ(d.points[k].abscissa, e.points[k].abscissa);  // threads change nothing
  }
  EXPECT_GT(stableCount(a), 10);
  EXPECT_LT(stableCount(a), 110);
}

TEST(StabilityChart, LugreTiresEnlargeTheStableRegionSlightly) {
  // (k_psi, k_y) chart of Fig 3 (tau1 = 0.2 s, p = 2000, tau2 = 0.1 ms) with both tire models.
  const ChartAxis x = ChartAxis::linear("tracker.k_psi", 0.0, 2.5, 26);
  const ChartAxis y = ChartAxis::linear("tracker.k_y", 0.0, 0.3, 31);
  const StabilityChart brush = computeStabilityChart(fig6("brush"), x, y);
  const StabilityChart lugre = computeStabilityChart(fig6("lugre_lumped"), x, y);
  int only_brush = 0, only_lugre = 0;
  for (std::size_t k = 0; k < brush.points.size(); ++k) {
    only_brush += brush.points[k].stable() && !lugre.points[k].stable();
    only_lugre += !brush.points[k].stable() && lugre.points[k].stable();
  }
  std::printf("  stable points of %zu: brush %d, lugre_lumped %d (only brush %d, only lugre %d)\n", brush.points.size(),
              stableCount(brush), stableCount(lugre), only_brush, only_lugre);
  EXPECT_EQ(only_brush, 0);
  EXPECT_GE(only_lugre, 1);
  EXPECT_LT(only_lugre, stableCount(brush) / 10);
}

TEST(StabilityChart, BadAxesAreClearErrors) {
  const SimConfig c = fig6();
  EXPECT_THROW(ChartAxis::linear("tracker.k_psi", 1.0, 0.0, 10), ConfigError);
  EXPECT_THROW(ChartAxis::linear("tracker.k_psi", 0.0, 1.0, 1), ConfigError);
  try {
    computeStabilityChart(c, ChartAxis::linear("tracker.kpsi", 0, 1, 3), ChartAxis::linear("tracker.k_y", 0, 1, 3));
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("tracker.kpsi"), std::string::npos) << e.what();
  }
  try {  // a negative delay at a corner
    computeStabilityChart(c, ChartAxis::linear("tau2", -1e-3, 1e-3, 3), ChartAxis::linear("tracker.k_y", 0, 1, 3));
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("delays."), std::string::npos) << e.what();
  }
}

/// lk_stability next to this test binary (same devel/lib directory), or "" if it was not built.
std::string toolPath() {
  char buffer[4096];
  const ssize_t n = readlink("/proc/self/exe", buffer, sizeof(buffer) - 1);
  if (n <= 0) return "";
  std::string path(buffer, static_cast<std::size_t>(n));
  path = path.substr(0, path.rfind('/')) + "/lk_stability";
  return std::ifstream(path).good() ? path : "";
}

int run(const std::string& command, std::string* out) {
  const std::string file = ::testing::TempDir() + "/lk_stability_test.out";
  const int status = std::system((command + " >" + file + " 2>&1").c_str());
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  *out = text.str();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(StabilityTool, CriticalPrintsOneJsonObject) {
  const std::string tool = toolPath();
  if (tool.empty()) GTEST_SKIP() << "lk_stability not built next to the tests";
  std::string out;
  ASSERT_EQ(run(tool + " critical --config " + scenario("fig9.yaml") + " 2>/dev/null", &out), 0) << out;
  const nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_NEAR(j.at("tau2_critical_s").get<double>(), 1.763006e-3, 1e-9);
  EXPECT_NEAR(j.at("frequency_hz").get<double>(), 128.898, 1e-3);
  EXPECT_FALSE(j.at("stable_at_configured").get<bool>());
  EXPECT_EQ(j.at("dde").at("dropped_states")[0], "x");
}

TEST(StabilityTool, BadInputIsAClearErrorWithStatus2) {
  const std::string tool = toolPath();
  if (tool.empty()) GTEST_SKIP() << "lk_stability not built next to the tests";
  std::string out;
  EXPECT_EQ(run(tool + " critical --config " + scenario("fig9.yaml") + " --set actuator.p=-5", &out), 2);
  EXPECT_NE(out.find("actuator.p"), std::string::npos) << out;
  EXPECT_EQ(run(tool + " chart --config " + scenario("fig6.yaml") + " --x tracker.k_psii:0:1:5 --y tracker.k_y:0:1:5 --out /tmp/x", &out), 2);
  EXPECT_NE(out.find("tracker.k_psii is not a numeric configuration key"), std::string::npos) << out;
  EXPECT_EQ(run(tool + " frobnicate --config " + scenario("fig6.yaml"), &out), 2);
  EXPECT_NE(out.find("unknown command"), std::string::npos) << out;
  EXPECT_EQ(run(tool + " critical --config /nonexistent.yaml", &out), 2);
  EXPECT_NE(out.find("/nonexistent.yaml"), std::string::npos) << out;
}

}  // namespace
}  // namespace lane_keeping
