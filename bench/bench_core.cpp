// Benchmark of the core simulator (issues #2, 49): the closed loop's real-time factor (simulated seconds
// per wall second, one core) for every tire model at dt = 1e-4 s and 1e-5 s, the cost of one closed-loop
// step (plant + controllers + delay lines + the 1 kHz log, per plant step at dt = 1e-4 s with one torque
// sample per step), and the cost of one model derivative. The step and the derivative are timed in the
// thread's CPU time as well as in wall time: on a shared machine the CPU time moves less with a neighbour's
// load (it still counts the cache and core a neighbour shares). Prints a table; numbers go in
// docs/benchmarks.md. Not a test: it asserts nothing.
//   lk_bench_core [--duration SECONDS] [--repeat N] [--tire MODEL]
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "lane_keeping/common/command_line.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/vehicle/single_track_model.h"

using namespace lane_keeping;

namespace {

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

/// The calling thread's CPU time [s].
double threadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

SimConfig fig6(const std::string& tire, double step, double duration) {
  // The paper's Fig 6 case (config/scenarios/fig6.yaml) with the tire model swapped.
  SimConfig c;
  c.simulation.name = "bench";
  c.simulation.initial.y = 1.0;
  c.simulation.step = step;
  c.simulation.duration = duration;
  c.tire_front.model = tire;
  c.tire_rear.model = tire;
  c.tracker.k_psi = 0.8;
  c.tracker.k_y = 0.01;
  c.actuator.p = 2000.0;
  c.actuator.rate = 1.0 / step;  // one torque sample per plant step, as in the default config
  c.delays.desired_steering_to_actuator = std::max(1e-4, step);
  c.delays.steering_angle_to_actuator = std::max(1e-4, step);
  if (tire == "lugre_distributed") c.tire_front.lugre.bristles = c.tire_rear.lugre.bristles = 50;
  return c;
}

double derivativeNanoseconds(const std::string& tire) {
  SimConfig c = fig6(tire, 1e-4, 1.0);
  const SingleTrackModel model = createVehicleModel(c.vehicle, c.tire_front, c.tire_rear);
  InitialState initial;
  initial.y = 0.3;
  initial.delta = 0.01;
  initial.sigma1 = 0.1;
  initial.sigma2 = 0.05;
  Eigen::VectorXd x = model.initialState(initial), x_dot(model.stateSize());
  const int n = 2000000;
  const double start = threadSeconds();
  double sink = 0.0;
  for (int i = 0; i < n; ++i) {
    x[kDelta] = 0.01 + 1e-9 * (i & 1023);
    model.derivative(x.data(), 1.0, x_dot.data());
    sink += x_dot[kSigma3];
  }
  const double ns = (threadSeconds() - start) / n * 1e9;  // CPU time
  if (sink == 12345.678) std::printf(" ");
  return ns;
}

}  // namespace

int main(int argc, char** argv) {
  double duration = 20.0;
  int repeat = 3;
  std::string only;  // one tire model, e.g. for profiling
  // Options read strictly (common/command_line.h): a bad value exits 2 naming it, as the tools do.
  try {
    for (int i = 1; i < argc; i += 2) {
      const std::string arg = argv[i];
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      if (arg == "--duration") duration = numberOption(arg, argv[i + 1], 0.01, 3600.0, "s");
      else if (arg == "--repeat") repeat = static_cast<int>(wholeNumberOption(arg, argv[i + 1], 1, 1000));
      else if (arg == "--tire") only = argv[i + 1];
      else throw UsageError("unknown argument '" + arg + "'");
    }
  } catch (const UsageError& e) {
    std::fprintf(stderr, "lk_bench_core: %s\n", e.what());
    return 2;
  }
  std::printf("lane_keeping core benchmark: Fig 6 closed loop (brush/LuGre tires), %g s simulated, best of %d,\n"
              "one core, log at 1 kHz; distributed LuGre with N = 50 bristles per direction.\n\n",
              duration, repeat);
  std::printf("%-18s %14s %14s %14s %16s %16s\n", "tire model", "derivative ns", "step ns (CPU)", "step ns (wall)",
              "RTF dt=1e-4 s", "RTF dt=1e-5 s");
  for (const std::string tire : {"brush", "lugre_lumped", "lugre_distributed", "magic_formula"}) {
    if (!only.empty() && tire != only) continue;
    std::printf("%-18s %14.1f", tire.c_str(), derivativeNanoseconds(tire));
    double rtf[2] = {0.0, 0.0}, step_cpu = 1e300, step_wall = 1e300;
    for (int k = 0; k < 2; ++k) {
      const double step = k == 0 ? 1e-4 : 1e-5;
      // dt = 1e-5 runs a tenth of the duration (same number of steps).
      const double simulated = step < 1e-4 ? duration / 10.0 : duration;
      const ClosedLoop loop(fig6(tire, step, simulated));
      double best = 1e300;
      for (int r = 0; r < repeat; ++r) {
        const auto start = std::chrono::steady_clock::now();
        const double cpu_start = threadSeconds();
        const RunResult result = loop.run();
        const double cpu = threadSeconds() - cpu_start;
        const double wall = seconds(std::chrono::steady_clock::now() - start);
        best = std::min(best, wall);
        if (k == 0) {
          step_cpu = std::min(step_cpu, cpu / result.plant_steps * 1e9);
          step_wall = std::min(step_wall, wall / result.plant_steps * 1e9);
        }
        if (result.diverged()) std::printf(" (diverged: %s)", result.message.c_str());
      }
      rtf[k] = simulated / best;
    }
    std::printf(" %14.1f %14.1f %15.0fx %15.0fx\n", step_cpu, step_wall, rtf[0], rtf[1]);
    std::fflush(stdout);
  }
  return 0;
}
