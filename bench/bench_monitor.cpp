// Benchmark of the live gap monitor (issue 17, item 4): the CPU one evaluation costs, and the share of
// one core the monitor needs to keep up with a run, at the input rate given. A closed-loop run of the
// "car" (the nominal configuration plus --truth assignments) is fed, row by row at --rate, into a
// GapMonitor of the nominal configuration, with sensor noise at the default levels (noise_reference.h)
// unless --no-noise (--set: assignments of both, e.g. the manoeuvre); every evaluation is timed on this thread's CPU clock.
//   lk_bench_monitor [--scenario FILE] [--rate HZ] [--duration S] [--truth key=value]... [--set key=value]... [--no-noise] [--seed N]
//                    [--sample-period S] [--window S] [--period S] [--draws N] [--reference-every S] [--max-floor F] [--warn E]
//                    [--quiet]
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "lane_keeping/common/command_line.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/evaluation/noise_reference.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/monitor/gap_monitor.h"
#include "lane_keeping/sim/closed_loop.h"
#include "build_paths.h"

using namespace lane_keeping;

namespace {
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
}  // namespace

int main(int argc, char** argv) {
  std::string source_dir = lane_keeping::build_paths::sourceDir();
  std::string scenario = source_dir + "/config/scenarios/lane_change.yaml";
  double rate = 1000.0, duration = 60.0;
  std::vector<std::string> truth, settings;
  bool noise = true, quiet = false;
  unsigned seed = 7;
  GapMonitorOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "lk_bench_monitor: %s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    try {
      if (arg == "--scenario") scenario = value();
      else if (arg == "--rate") rate = numberOption(arg, value(), 1.0, 1e4, "Hz");
      else if (arg == "--duration") duration = numberOption(arg, value(), 0.1, 1e5, "s");
      else if (arg == "--truth") truth.push_back(value());
      else if (arg == "--set") settings.push_back(value());
      else if (arg == "--no-noise") noise = false;
      else if (arg == "--seed") seed = static_cast<unsigned>(wholeNumberOption(arg, value(), 0, 4294967295LL));
      else if (arg == "--quiet") quiet = true;
      else if (arg == "--sample-period") options.sample_period = numberOption(arg, value(), 1e-6, 10.0, "s");
      else if (arg == "--window") options.window = numberOption(arg, value(), 1e-3, 1e4, "s");
      else if (arg == "--period") options.period = numberOption(arg, value(), 1e-3, 1e4, "s");
      else if (arg == "--max-floor") options.max_floor = numberOption(arg, value(), 0.0, 1e6);
      else if (arg == "--warn") options.warn_excess = numberOption(arg, value(), 0.0, 1e6);
      else if (arg == "--draws") options.reference_draws = static_cast<int>(wholeNumberOption(arg, value(), 0, 19));
      else if (arg == "--reference-every") options.reference_every = numberOption(arg, value(), 0.0, 1e5, "s");
      else {
        std::fprintf(stderr, "lk_bench_monitor: unknown argument %s\n", arg.c_str());
        return 2;
      }
    } catch (const UsageError& e) {
      std::fprintf(stderr, "lk_bench_monitor: %s\n", e.what());
      return 2;
    }
  }
  try {
    const std::vector<std::string> files{source_dir + "/config/default.yaml", scenario};
    std::vector<std::string> run_settings{"simulation.duration=" + std::to_string(duration),
                                          "simulation.log_rate=" + std::to_string(rate)};
    run_settings.insert(run_settings.end(), settings.begin(), settings.end());
    const SimConfig nominal = loadSimConfig(files, run_settings);
    std::vector<std::string> car_settings = run_settings;
    car_settings.insert(car_settings.end(), truth.begin(), truth.end());
    const RunResult run = ClosedLoop(loadSimConfig(files, car_settings)).run();
    GapLog log = gapLogFromRows(run.rows, "bench");
    if (noise) addSensorNoise(log, SensorNoise{}, seed);
    std::printf("lane_keeping gap monitor benchmark: %s, %.0f s at %.0f Hz input, replays at %.0f Hz, window %.0f s, "
                "every %.1f s%s%s\n",
                scenario.substr(scenario.find_last_of('/') + 1).c_str(), duration, rate, 1.0 / options.sample_period,
                options.window, options.period, noise ? ", sensor noise" : "", truth.empty() ? ", no effect" : "");
    for (const auto& t : truth) std::printf("  car: %s\n", t.c_str());

    GapMonitor monitor(nominal, options);
    std::vector<double> costs;
    double ingest_cpu = 0.0;
    int warn_or_worse = 0;
    for (std::size_t i = 0; i < log.size(); ++i) {
      const double c0 = threadCpuSeconds();
      MonitorStateSample s;
      s.t = log.t[i];
      s.x = log.x[i];
      s.y = log.y[i];
      s.psi = log.psi[i];
      s.yaw_rate = log.yaw_rate[i];
      s.delta = log.delta[i];
      s.delta_rate = log.delta_rate[i];
      s.speed = log.v[i];
      s.lateral_acceleration = log.ay[i];
      s.torque_applied = log.torque[i];
      monitor.window().addState(s);
      monitor.window().addDesired(log.t[i], log.delta_des[i]);
      monitor.window().addTorque(log.t[i], log.torque[i]);
      ingest_cpu += threadCpuSeconds() - c0;
      if (!monitor.due()) continue;
      const double e0 = threadCpuSeconds();
      const MonitorStatus status = monitor.evaluate();
      costs.push_back(threadCpuSeconds() - e0);
      if (status.level == MonitorLevel::kWarn || status.level == MonitorLevel::kError) ++warn_or_worse;
      if (quiet) continue;
      std::printf("t %6.2f %-5s", status.stamp, monitorLevelName(status.level));
      for (const auto& sub : status.subsystems) {
        std::printf("  %s %s %.4f f%.2f", sub.name.c_str(), monitorLevelName(sub.level), sub.net, sub.floor);
      }
      std::printf("  lead %s [%.1f, %.1f) s %.0f-%.0f Hz  %.0f ms%s\n", status.leading.c_str(), status.leading_t0,
                  status.leading_t1, status.band_f0, status.band_f1, 1e3 * costs.back(),
                  status.reference_refreshed ? " (reference)" : "");
      for (const auto& note : status.notes) std::printf("    note: %s\n", note.c_str());
      for (const auto& sub : status.subsystems) {
        if (sub.level != MonitorLevel::kOk) {
          std::printf("    %s: nrmse %.4f floor %.4f excess %.4f reference %.4f\n", sub.name.c_str(), sub.nrmse, sub.floor,
                      sub.excess, sub.reference);
        }
      }
    }
    std::sort(costs.begin(), costs.end());
    double total = 0.0;
    for (double c : costs) total += c;
    const double span = log.t.back() - log.t.front();
    std::printf("\n%zu evaluations: CPU per evaluation median %.0f ms, max %.0f ms; ingest %.2f us/row\n", costs.size(),
                costs.empty() ? 0.0 : 1e3 * costs[costs.size() / 2], costs.empty() ? 0.0 : 1e3 * costs.back(),
                1e6 * ingest_cpu / std::max<std::size_t>(1, log.size()));
    std::printf("share of one core at real time: %.1f %% (CPU %.2f s for %.0f s of data); WARN/ERROR evaluations: %d\n",
                100.0 * (total + ingest_cpu) / span, total + ingest_cpu, span, warn_or_worse);
  } catch (const LaneKeepingError& e) {
    std::fprintf(stderr, "lk_bench_monitor: %s\n", e.what());
    return 2;
  }
  return 0;
}
