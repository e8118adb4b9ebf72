#include "lane_keeping/gap/decision/where_analysis.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <set>

#include "lane_keeping/gap/replay/subsystem_replay.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Residual energy above the noise floor of each sample of a subsystem: sum over its traces of
/// max(0, r^2 - floor^2), with the sample times and the data set each sample belongs to.
void excessEnergy(const SubsystemReplay& replay, const SubsystemScore& score, const std::vector<std::size_t>& starts,
                  std::vector<double>* t, std::vector<double>* e, std::vector<std::size_t>* set) {
  for (std::size_t k = 0; k < replay.traces.size(); ++k) {
    const auto r = replay.traces[k].residual();
    const double f2 = score.traces[k].floor * score.traces[k].floor;
    std::size_t d = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      while (d + 1 < starts.size() && i >= starts[d + 1]) ++d;
      t->push_back(replay.traces[k].t[i]);
      e->push_back(std::max(0.0, r[i] * r[i] - f2) / std::max<std::size_t>(1, r.size()));
      set->push_back(d);
    }
  }
}

/// Whether a run's gap sets in mid-run (a crosswind past a cutting, a fault): the first of its windows by
/// which kOnsetShare of the excess energy has accrued lies at least kOnsetFraction into the run. A gap
/// present from the start accrues ~1/bins per window and never qualifies.
constexpr double kOnsetShare = 0.05, kOnsetFraction = 0.25;
bool setsInMidRun(const std::vector<double>& energy) {
  double total = 0.0;
  for (double e : energy) total += e;
  if (!(total > 0.0) || energy.size() < 8) return false;
  double accrued = 0.0;
  for (std::size_t b = 0; b < energy.size(); ++b) {
    accrued += energy[b];
    if (accrued > kOnsetShare * total) return b >= kOnsetFraction * energy.size();
  }
  return false;
}

/// Where a run's excess energy steps up: the time at which its cumulative energy S(t) lies farthest below
/// the line of uniform accrual, S(t) - S_total (t - t_min) / (t_max - t_min) — the least-squares change
/// point of a step in the energy's mean (Page's CUSUM; Basseville & Nikiforov, Detection of Abrupt
/// Changes, 1993, sect. 2.6). Sample by sample, not by window: the start of the window in which 5 % had
/// accrued, reported before, was off by up to a window (1.25 s of a 30 s run, 2.5 s of a 60 s one) and
/// early by the noise's share of the excess (errors of 1-4 s).
double energyStep(std::vector<std::pair<double, double>> samples, double t_min, double t_max) {
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  double total = 0.0;
  for (const auto& s : samples) total += s.second;
  double accrued = 0.0, lowest = 0.0, at = t_min;
  for (const auto& [t, e] : samples) {
    const double below = accrued - total * (t - t_min) / (t_max - t_min);  // S just before t
    if (below < lowest) {
      lowest = below;
      at = t;
    }
    accrued += e;
  }
  return at;
}

/// Welch power spectral density of a uniformly resampled series (Hann windows, 50 % overlap).
void welch(const std::vector<double>& x, double dt, std::vector<double>* f, std::vector<double>* psd) {
  const std::size_t n = x.size();
  std::size_t len = 256;
  while (len > 16 && len > n) len /= 2;
  f->clear();
  psd->clear();
  if (n < 16) return;
  std::vector<double> w(len);
  double wss = 0.0;
  for (std::size_t i = 0; i < len; ++i) {
    w[i] = 0.5 - 0.5 * std::cos(2.0 * M_PI * i / (len - 1));
    wss += w[i] * w[i];
  }
  Eigen::FFT<double> fft;
  std::vector<double> acc(len / 2 + 1, 0.0), chunk(len);
  std::vector<std::complex<double>> spectrum;
  int count = 0;
  for (std::size_t start = 0; start + len <= n; start += len / 2) {
    double mean = 0.0;
    for (std::size_t i = 0; i < len; ++i) mean += x[start + i];
    mean /= len;
    for (std::size_t i = 0; i < len; ++i) chunk[i] = (x[start + i] - mean) * w[i];
    fft.fwd(spectrum, chunk);
    for (std::size_t k = 0; k <= len / 2; ++k) acc[k] += std::norm(spectrum[k]);
    ++count;
  }
  for (std::size_t k = 0; k <= len / 2; ++k) {
    f->push_back(k / (len * dt));
    const double one_sided = (k == 0 || k == len / 2) ? 1.0 : 2.0;
    psd->push_back(one_sided * acc[k] * dt / (wss * std::max(1, count)));
  }
}

/// The residual of a subsystem as one series at the log rate (RMS over its traces), time-sorted.
std::vector<std::pair<double, double>> subsystemSeries(const SubsystemReplay& replay) {
  std::map<double, std::pair<double, int>> acc;
  for (const auto& trace : replay.traces) {
    const auto r = trace.residual();
    for (std::size_t i = 0; i < r.size(); ++i) {
      auto& a = acc[trace.t[i]];
      a.first += r[i] * r[i];
      a.second += 1;
    }
  }
  std::vector<std::pair<double, double>> out;
  for (const auto& [t, a] : acc) out.emplace_back(t, std::sqrt(a.first / a.second));
  return out;
}

/// Signed residual series of the first trace (for spectra: RMS would rectify).
std::vector<double> signedSeries(const SubsystemReplay& replay, double* dt) {
  std::vector<double> values;
  if (replay.traces.empty() || replay.traces[0].t.size() < 2) return values;
  const auto& trace = replay.traces[0];
  const auto r = trace.residual();
  std::vector<double> steps;
  for (std::size_t i = 1; i < trace.t.size(); ++i) {
    if (trace.t[i] > trace.t[i - 1]) steps.push_back(trace.t[i] - trace.t[i - 1]);
  }
  std::sort(steps.begin(), steps.end());
  *dt = steps.empty() ? 0.01 : steps[steps.size() / 2];
  return r;
}

/// The chassis residual must be this many times its noise floor to count as an upstream cause.
constexpr double kUpstreamSignalToNoise = 2.0;

}  // namespace

GapWhere whereAnalysis(const Evaluation& ev, const std::vector<Dataset>& data, double upstream_share,
                       DiagnosisArtifacts* artifacts) {
  GapWhere where;
  double best = -1.0;
  for (const std::string& name : subsystemNames()) {
    const auto it = ev.scores.find(name);
    if (it == ev.scores.end()) continue;
    SubsystemGap g;
    g.name = name;
    g.nrmse = it->second.nrmse;
    g.noise_floor = it->second.floor;
    for (const auto& t : it->second.traces) g.outputs.push_back(t.name);
    where.subsystems.push_back(g);
    // Ranked by the excess beyond the noise-only reference: what noise alone leaves in a replay is not
    // a gap (ranked by raw excess, a 60 s, 1 kHz column log whose actuator noise excess matched its
    // reference was placed in the actuator, which no candidate changes, and judged unexplained).
    if (netExcess(it->second) > best) {
      best = netExcess(it->second);
      where.subsystem = name;
    }
  }
  // The steering replay takes the chassis replay's lateral velocity, and its tiny inertia J_F amplifies
  // any aligning-moment mismatch: a chassis cause shows in both, often more in the steering. A pure
  // steering effect leaves the chassis at its noise floor. So the chassis is reported when it carries
  // a real share of the steering's excess and stands clearly above its own noise floor. (A steering
  // effect that shakes the wheel fast — e.g. a torque limit that lets the steering loop chatter — can
  // leave the chassis replay of the sampled angle noisy in one trace: excess, but not above the floor.)
  if (where.subsystem == "steering" && ev.scores.count("chassis")) {
    const SubsystemScore& chassis = ev.scores.at("chassis");
    if (netExcess(chassis) >= upstream_share * netExcess(ev.scores.at("steering")) && netExcess(chassis) > 0.005 &&
        chassis.nrmse >= kUpstreamSignalToNoise * chassis.floor) {
      where.subsystem = "chassis";
    }
  }
  if (where.subsystem.empty()) return where;
  const SubsystemReplay& replay = ev.replays.at(where.subsystem);
  const SubsystemScore& score = ev.scores.at(where.subsystem);

  // Windows: excess energy per time window of the dominant subsystem, in each run's own time (runs
  // of different roads share times; a log split into blocks is one run).
  std::vector<double> t, e;
  std::vector<std::size_t> set;
  const auto starts_it = ev.starts.find(where.subsystem);
  excessEnergy(replay, score, starts_it == ev.starts.end() ? std::vector<std::size_t>{} : starts_it->second, &t, &e, &set);
  double total = 0.0;
  for (double x : e) total += x;
  std::map<const LogSignals*, std::pair<double, double>> span;  // per run: first and last sample time
  for (std::size_t i = 0; i < t.size(); ++i) {
    const LogSignals* log = data[set[i]].log.get();
    auto it = span.find(log);
    if (it == span.end()) span[log] = {t[i], t[i]};
    else it->second = {std::min(it->second.first, t[i]), std::max(it->second.second, t[i])};
  }
  std::vector<std::pair<const LogSignals*, RunOnset>> onsets;
  if (total > 0.0) {
    std::vector<WindowShare> windows;
    for (const auto& [log, range] : span) {
      const double t_min = range.first, t_max = range.second;
      if (!(t_max > t_min)) continue;
      const double width = std::max(0.5, (t_max - t_min) / 24.0);
      const int bins = static_cast<int>(std::ceil((t_max - t_min) / width + 1e-9));
      std::vector<double> energy(std::max(1, bins), 0.0);
      for (std::size_t i = 0; i < t.size(); ++i) {
        if (data[set[i]].log.get() != log) continue;
        energy[std::min(bins - 1, static_cast<int>((t[i] - t_min) / width))] += e[i];
      }
      for (int b = 0; b < bins; ++b) {
        windows.push_back({log->log().source, t_min + b * width, t_min + (b + 1) * width, energy[b] / total, log->start()});
      }
      // Each run's own onset, the training and the held-out runs alike (a pair of runs had none before).
      if (setsInMidRun(energy)) {
        std::vector<std::pair<double, double>> samples;
        for (std::size_t i = 0; i < t.size(); ++i) {
          if (data[set[i]].log.get() == log) samples.emplace_back(t[i], e[i]);
        }
        onsets.push_back({log, RunOnset{log->log().source, energyStep(std::move(samples), t_min, t_max), log->start()}});
      }
    }
    std::stable_sort(windows.begin(), windows.end(), [](const auto& a, const auto& b) { return a.share > b.share; });
    windows.resize(std::min<std::size_t>(5, windows.size()));
    where.windows = windows;
  }
  // In the order of the runs (training, then held-out), not of their addresses.
  std::set<const LogSignals*> listed;
  for (const Dataset& set : data) {
    if (!listed.insert(set.log.get()).second) continue;
    for (const auto& [log, onset] : onsets) {
      if (log == set.log.get()) where.onsets.push_back(onset);
    }
  }
  if (span.size() == 1 && where.onsets.size() == 1) where.onset = where.onsets[0].t;

  // Bands: spectrum of the dominant subsystem's residual minus its white-noise level.
  double dt = 0.01;
  const std::vector<double> series = signedSeries(replay, &dt);
  std::vector<double> f, psd;
  welch(series, dt, &f, &psd);
  if (!f.empty()) {
    const double noise_psd = 2.0 * dt * score.traces[0].floor * score.traces[0].floor;
    const double nyquist = 0.5 / dt;
    std::vector<double> edges{0.0, 0.5, 2.0, 8.0, 32.0};
    edges.erase(std::remove_if(edges.begin(), edges.end(), [&](double x) { return x >= nyquist; }), edges.end());
    edges.push_back(nyquist);
    std::vector<double> energy(edges.size() - 1, 0.0);
    double sum = 0.0;
    const double df = f.size() > 1 ? f[1] - f[0] : 1.0;
    for (std::size_t k = 1; k < f.size(); ++k) {
      const double excess = std::max(0.0, psd[k] - noise_psd) * df;
      for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
        if (f[k] >= edges[b] && (f[k] < edges[b + 1] || b + 2 == edges.size())) {
          energy[b] += excess;
          break;
        }
      }
      sum += excess;
    }
    for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
      where.bands.push_back({edges[b], edges[b + 1], sum > 0.0 ? energy[b] / sum : 0.0});
    }
  }

  // Regimes: share of the excess energy vs share of samples in bins of |front slip angle|, |a_y|,
  // |steering rate| (from the log; the slip angle with the chassis replay's lateral velocity). V is the
  // logged speed where the log has one (a real run goes from 8 to 20 m/s), else the configured one.
  struct Binning {
    std::string name;
    std::vector<double> edges;
  };
  const std::vector<Binning> binnings{{"slip_angle", {0.0, 0.0087, 0.0175, 0.035, 0.07, 1e9}},
                                      {"lateral_acceleration", {0.0, 0.5, 1.0, 2.0, 4.0, 1e9}},
                                      {"steering_rate", {0.0, 0.02, 0.05, 0.1, 0.3, 1e9}}};
  for (const auto& binning : binnings) {
    std::vector<double> energy(binning.edges.size() - 1, 0.0), count(binning.edges.size() - 1, 0.0);
    double e_sum = 0.0, n_sum = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const LogSignals* log = data[set[i]].log.get();
      const SimConfig& config = *data[set[i]].config;
      const double b_front = config.vehicle.cgToFrontAxle();
      const double V = log->has(LogSignals::kSpeed) ? std::max(1.0, std::fabs(log->at(LogSignals::kSpeed, t[i])))
                                                    : config.vehicle.speed;
      double value = 0.0;
      if (binning.name == "slip_angle") {
        // (A log without a measured lateral velocity, no pose or a course for a heading: 0, a slip from
        // the steering and yaw rate alone.)
        const double sigma1 = log->has(LogSignals::kSigma1) ? log->at(LogSignals::kSigma1, t[i]) : 0.0;
        value = std::fabs(log->at(LogSignals::kDelta, t[i]) - (sigma1 + b_front * log->at(LogSignals::kYawRate, t[i])) / V);
      } else if (binning.name == "lateral_acceleration") {
        value = log->has(LogSignals::kLateralAcceleration) ? std::fabs(log->at(LogSignals::kLateralAcceleration, t[i]))
                                                           : std::fabs(V * log->at(LogSignals::kYawRate, t[i]));
      } else {
        value = std::fabs(log->at(LogSignals::kDeltaRate, t[i]));
      }
      for (std::size_t b = 0; b + 1 < binning.edges.size(); ++b) {
        if (value >= binning.edges[b] && value < binning.edges[b + 1]) {
          energy[b] += e[i];
          count[b] += 1.0;
          break;
        }
      }
      e_sum += e[i];
      n_sum += 1.0;
    }
    for (std::size_t b = 0; b + 1 < binning.edges.size(); ++b) {
      if (count[b] == 0.0) continue;
      RegimeShare r;
      r.variable = binning.name;
      r.lo = binning.edges[b];
      r.hi = binning.edges[b + 1] > 1e8 ? std::numeric_limits<double>::infinity() : binning.edges[b + 1];
      r.share = e_sum > 0.0 ? energy[b] / e_sum : 0.0;
      r.time_share = n_sum > 0.0 ? count[b] / n_sum : 0.0;
      where.regimes.push_back(r);
    }
  }

  if (artifacts != nullptr) {
    // residuals.csv: per subsystem RMS-over-outputs residual on a common time base.
    std::map<std::string, std::vector<std::pair<double, double>>> series_by_name;
    std::set<double> times;
    for (const auto& [name, r] : ev.replays) {
      series_by_name[name] = subsystemSeries(r);
      for (const auto& p : series_by_name[name]) times.insert(p.first);
    }
    // Written afresh (a diagnosis from the onset writes them after the whole log's: appended columns were
    // the whole log's residuals against the later times, and a subsystem only the first replayed stayed).
    artifacts->residual.clear();
    artifacts->spectrum.clear();
    artifacts->residual_t.assign(times.begin(), times.end());
    for (const auto& [name, s] : series_by_name) {
      std::map<double, double> lookup(s.begin(), s.end());
      auto& column = artifacts->residual[name];
      for (double time : artifacts->residual_t) {
        const auto it = lookup.find(time);
        column.push_back(it == lookup.end() ? kNaN : it->second);
      }
    }
    // spectrum.csv on the dominant subsystem's frequency grid.
    artifacts->spectrum_f = f;
    for (const auto& [name, r] : ev.replays) {
      double step = 0.01;
      std::vector<double> fs, ps;
      welch(signedSeries(r, &step), step, &fs, &ps);
      std::vector<double> column;
      for (double fk : f) {
        double value = kNaN;
        for (std::size_t k = 0; k + 1 < fs.size(); ++k) {
          if (fk >= fs[k] && fk <= fs[k + 1]) {
            const double w = (fk - fs[k]) / std::max(1e-12, fs[k + 1] - fs[k]);
            value = ps[k] + w * (ps[k + 1] - ps[k]);
            break;
          }
        }
        column.push_back(value);
      }
      artifacts->spectrum[name] = column;
    }
  }
  return where;
}

}  // namespace diagnosis
}  // namespace lane_keeping
