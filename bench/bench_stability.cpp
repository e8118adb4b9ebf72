// lk_bench_stability: wall time of a 100 x 100 stability chart in the (k_psi, k_y) plane (Beregi
// Fig 3 set-up: tau1 = 0.2 s, tau2 = 0.1 ms, p = 2000) on 1 and on all cores, per tire model, and
// of the pieces one chart point costs. Prints figures; asserts nothing.
//   lk_bench_stability [--n N] [--degree M]
#include <chrono>
#include <iomanip>
#include <iostream>
#include <malloc.h>
#include <string>
#include <thread>

#include "lane_keeping/common/command_line.h"
#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "lane_keeping/analysis/stability_boundary.h"
#include "lane_keeping/analysis/stability_chart.h"

namespace {

using namespace lane_keeping;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

SimConfig paperConfig(const std::string& tire) {
  return loadSimConfig({}, {"tire.front.model=" + tire, "tire.rear.model=" + tire, "tracker.k_psi=0.8", "tracker.k_y=0.01",
                            "actuator.p=2000", "delays.pose_to_tracker=0.2", "delays.desired_steering_to_actuator=1e-4",
                            "delays.steering_angle_to_actuator=1e-4"});
}

}  // namespace

int main(int argc, char** argv) {
  // As lk_stability: keep freed chart-point matrices in the heap instead of trimming it each time.
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mallopt(M_TOP_PAD, 16 << 20);
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  int n = 100, degree = 0;
  // Options read strictly (common/command_line.h): a bad value exits 2 naming it, as the tools do.
  try {
    for (int i = 1; i < argc; i += 2) {
      const std::string arg = argv[i];
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      if (arg == "--n") n = static_cast<int>(wholeNumberOption(arg, argv[i + 1], 2, 1000));
      else if (arg == "--degree") degree = static_cast<int>(wholeNumberOption(arg, argv[i + 1], 2, 400));
      else throw UsageError("unknown argument '" + arg + "'");
    }
  } catch (const UsageError& e) {
    std::cerr << "lk_bench_stability: " << e.what() << "\n";
    return 2;
  }
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  std::cout << std::fixed << std::setprecision(3);
  std::cout << "stability chart benchmark: " << n << " x " << n << " grid, k_psi in [0, 2.5], k_y in [0, 0.3] 1/m, "
            << cores << " hardware threads\n";
  for (const std::string tire : {"brush", "lugre_lumped"}) {
    const SimConfig config = paperConfig(tire);
    ChartOptions options;
    if (degree > 0) options.spectrum.degree = degree;
    // Cost of one point's pieces.
    const int reps = 200;
    auto start = Clock::now();
    ClosedLoopLinearization lin;
    for (int r = 0; r < reps; ++r) lin = linearizeClosedLoop(config);
    const double t_lin = since(start) / reps;
    start = Clock::now();
    Spectrum s;
    for (int r = 0; r < reps; ++r) s = computeSpectrum(lin.dde, options.spectrum);
    const double t_spec = since(start) / reps;
    std::cout << "\n" << tire << ": " << lin.dde.size() << " DDE states, collocation matrix order " << s.dimension
              << " (degree " << options.spectrum.degree << " per delay line)\n"
              << "  per point: linearise " << t_lin * 1e3 << " ms, spectrum + Newton " << t_spec * 1e3 << " ms\n";
    const ChartAxis x = ChartAxis::linear("tracker.k_psi", 0.0, 2.5, n);
    const ChartAxis y = ChartAxis::linear("tracker.k_y", 0.0, 0.3, n);
    for (int threads : {1, cores}) {
      options.threads = threads;
      const StabilityChart chart = computeStabilityChart(config, x, y, options);
      int stable = 0;
      for (const auto& p : chart.points) stable += p.stable() ? 1 : 0;
      std::cout << "  " << n << "x" << n << " chart, " << chart.threads << " thread(s): " << chart.wall_seconds << " s ("
                << stable << " stable points)\n";
      if (cores == 1) break;
    }
    start = Clock::now();
    ScanOptions scan;
    const Crossing c = findFirstCrossing(configFamily(config, "tau2"), scan);
    std::cout << "  critical tau2 (scan + refinement, " << c.spectra << " spectra): " << since(start) << " s -> "
              << std::setprecision(6) << c.parameter * 1e3 << " ms, " << c.frequencyHz() << " Hz" << std::setprecision(3) << "\n";
  }
  return 0;
}
