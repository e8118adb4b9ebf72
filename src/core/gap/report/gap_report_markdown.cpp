// DIR/report.md: the human-readable gap report (layout in gap_report_markdown.h).
#include "lane_keeping/gap/report/gap_report_markdown.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <system_error>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kWindowsShown = 5;

std::string num(double v, const char* format = "%.4g") {
  if (!std::isfinite(v)) return "n/a";
  char buffer[48];
  std::snprintf(buffer, sizeof(buffer), format, v);
  return buffer;
}

std::string percent(double fraction) { return std::isfinite(fraction) ? num(100.0 * fraction, "%.1f") + " %" : "n/a"; }

double shrinkOf(double before, double after) {
  return (std::isfinite(before) && before > 0.0 && std::isfinite(after)) ? 1.0 - after / before
                                                                        : std::numeric_limits<double>::quiet_NaN();
}

/// Text for a table cell: '|' escaped, newlines flattened.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += "\\|";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out.empty() ? "-" : out;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

std::vector<std::string> splitDots(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

/// The overlay {"a.b.c": "1"} as nested YAML, a:\n  b:\n    c: 1
std::string nestedYaml(const std::map<std::string, std::string>& overlay) {
  std::vector<std::pair<std::vector<std::string>, std::string>> entries;
  for (const auto& [key, value] : overlay) entries.emplace_back(splitDots(key), value);
  std::sort(entries.begin(), entries.end());
  std::ostringstream out;
  std::vector<std::string> open;  // the mapping keys currently open
  for (const auto& [parts, value] : entries) {
    std::size_t common = 0;
    while (common < open.size() && common + 1 < parts.size() && open[common] == parts[common]) ++common;
    open.resize(common);
    for (std::size_t i = common; i + 1 < parts.size(); ++i) {
      out << std::string(2 * i, ' ') << parts[i] << ":\n";
      open.push_back(parts[i]);
    }
    out << std::string(2 * (parts.size() - 1), ' ') << parts.back() << ": " << value << "\n";
  }
  return out.str();
}

std::string paramsWithSigma(const RankedEffect& e) {
  std::vector<std::string> items;
  for (const auto& [name, value] : e.params) {
    std::string item = name + " = " + num(value);
    const auto sigma = e.param_sigma.find(name);
    if (sigma != e.param_sigma.end()) item += " ± " + num(sigma->second, "%.2g");
    items.push_back(item);
  }
  return items.empty() ? "-" : join(items, ", ");
}

const RankedEffect* findEffect(const GapReport& report, const std::string& effect) {
  for (const RankedEffect& e : report.ranking)
    if (e.effect == effect) return &e;
  return nullptr;
}

void writeVerdict(std::ostream& out, const GapReport& r) {
  const GapVerdict& v = r.verdict;
  out << "## Verdict\n\n";
  const bool unexplained = v.effect.empty() || v.effect == "unexplained";
  out << "**" << (unexplained ? std::string("unexplained") : v.effect) << "**"
      << (v.form.empty() ? std::string() : " (" + v.form + ")") << " (confidence " << num(v.confidence, "%.2f") << ")\n\n";
  out << "- held-out gap: " << num(v.gap_before) << " → " << num(v.gap_after) << " (shrink " << percent(v.shrink)
      << ")\n";
  if (v.basis == "modal") {
    out << "- named on: the steering loop's modes (its roots against the logged ringing), not on the replays: the "
           "held-out gap is left as it was\n";
  }
  if (v.basis == "targeted") {
    out << "- named on: a test aimed at a steering-loop delay (its fit against the same fit on the noise-only "
           "draws), where the replays' own test sees no gap; the held-out gap is the delay's subsystems', gross of the "
           "noise reference\n";
  }
  if (v.basis == "measured") {
    out << "- named on: the input checks' measurement before any model (the gyro laid over psi and ay / V), "
           "corrected before the fits; the gap before is the logs' as they were\n";
  }
  if (!v.reason.empty()) out << "- reason: " << v.reason << "\n";
  if (v.effects.size() == 1 && !v.effects.front().replay_params.empty()) {
    // closed_loop_placement.h: the values to simulate with are the placed ones.
    const VerdictEffect& e = v.effects.front();
    out << "- placed by the closed loop of the training runs (among the values the replays cannot tell apart):";
    for (const auto& [name, value] : e.params) {
      const auto fitted = e.replay_params.find(name);
      out << " " << name << " " << num(value, "%.4g")
          << (fitted != e.replay_params.end() ? " (the replays' fit " + num(fitted->second, "%.4g") + ")" : "");
    }
    out << "\n";
  }
  out << "- confusable with: " << (v.confusable_with.empty() ? "none reported" : join(v.confusable_with, ", "))
      << "\n";
  const GapDetection& d = r.detection;
  if (d.draws > 0) {
    out << "- is there a gap? total excess of the nominal replays against " << d.draws
        << " noise-only draws (Monte Carlo test at " << percent(d.false_alarm_rate) << "): held-out "
        << num(d.heldout.value, "%.3g") << ", p = " << num(d.heldout.p_value, "%.3f")
        << (d.heldout.detected ? " (a gap)" : " (within noise)") << "; training " << num(d.training.value, "%.3g")
        << ", p = " << num(d.training.p_value, "%.3f") << (d.training.detected ? " (a gap)" : " (within noise)")
        << "; both together " << num(d.pooled.value, "%.3g") << ", p = " << num(d.pooled.p_value, "%.3f")
        << (d.pooled.detected ? " (a gap)" : " (within noise)") << "; draws: median "
        << num(d.heldout.null_median, "%.3g") << ", largest " << num(d.heldout.null_max, "%.3g") << "\n";
  } else {
    out << "- is there a gap? not tested: no noise-only draw could run (see the notes); the diagnosis went on "
           "where the held-out gap reached the detection threshold\n";
  }
  if (!r.folds.empty()) {
    if (r.folds.size() > 2) {
      out << "- each run held out in turn, fitted on the others (the verdict decided on the held-out evidence summed "
             "over them):\n";
    } else if (r.detection.heldout.detected) {
      out << "- each side held out in turn (asked for):\n";
    } else {
      out << "- each side held out in turn (the held-out test alone missed the gap, both sides together saw it):\n";
    }
    for (std::size_t k = 0; k < r.folds.size(); ++k) {
      const GapFold& f = r.folds[k];
      out << "  - fold " << (k + 1) << ", fitted on " << join(f.training, ", ") << ", scored on " << join(f.heldout, ", ")
          << " (held-out p = " << num(f.heldout_p, "%.3f") << "): " << f.effect << (f.form.empty() ? "" : " (" + f.form + ")");
      if (f.effect != "unexplained") out << ", held-out gap " << num(f.gap_before) << " → " << num(f.gap_after);
      for (const auto& [name, value] : f.params) out << ", " << name << " " << num(value, "%.4g");
      out << "\n";
    }
  }
  if (v.effects.size() > 1) {
    out << "- effects named (each fitted on top of those before it, its share of the held-out gap):\n";
    for (const VerdictEffect& e : v.effects) {
      out << "  - " << e.effect << (e.form.empty() ? "" : " (" + e.form + ")") << (e.sensor ? " [sensor error]" : "")
          << (e.measured ? " [measured before any model]" : "") << ": " << percent(e.share);
      for (const auto& [name, value] : e.params) out << ", " << name << " " << num(value, "%.4g");
      if (!e.confusable_with.empty()) out << " (confusable with: " << join(e.confusable_with, ", ") << ")";
      out << "\n";
    }
    out << "  - together: held-out gap " << num(v.gap_before) << " → " << num(v.combined_gap_after) << " (shrink "
        << percent(v.combined_shrink) << ")\n";
  }
  if (!v.partial.effect.empty()) {
    out << "- partial explanation: " << v.partial.effect << (v.partial.form.empty() ? "" : " (" + v.partial.form + ")")
        << " removes " << percent(v.partial.share) << " of the gap; " << percent(v.partial.untouched_share)
        << " of it lies in subsystems it does not change; its residual: whiteness p = "
        << num(v.partial.whiteness_p, "%.3f") << ", correlation with the input p = "
        << num(v.partial.input_correlation_p, "%.3f") << "\n";
  }
  for (const auto& s : r.skipped_subsystems) {
    out << "- skipped: the " << s.name << " replay (" << s.reason << ")\n";
  }
  if (!r.not_testable.empty()) {
    std::vector<std::string> names;
    for (const auto& e : r.not_testable) names.push_back(e.effect + " (" + e.reason + ")");
    out << "- not testable on these logs (not rejected): " << join(names, "; ") << "\n";
  }
  if (!r.not_fitted.empty()) {
    std::vector<std::string> names;
    for (const auto& e : r.not_fitted) names.push_back(e.effect);
    out << "- not fitted (" << r.not_fitted.front().reason << "): " << join(names, ", ") << "\n";
  }
  if (!r.split.method.empty()) {
    std::vector<std::string> coverage;
    for (const auto& [kind, share] : r.split.coverage) coverage.push_back(kind + " " + percent(share));
    out << "- held-out data: " << r.split.method << " (held-out share of each excitation: " << join(coverage, ", ")
        << ")\n";
  }
  out << "\n";

  const RankedEffect* winner = unexplained ? nullptr : findEffect(r, v.effect);
  if (unexplained) {
    out << "No candidate effect earned its extra parameters on held-out data; no config overlay is proposed.\n\n";
  } else if (winner && !winner->config.empty()) {
    out << "### Config overlay that adds the effect\n\n";
    out << "Add to the nominal config (or pass as `--set`):\n\n```yaml\n" << nestedYaml(winner->config) << "```\n\n";
    std::vector<std::string> sets;
    for (const auto& [key, value] : winner->config) sets.push_back("--set " + key + "=" + value);
    out << "```\n" << join(sets, " ") << "\n```\n\n";
  } else {
    out << "(no config overlay recorded for " << v.effect << ")\n\n";
  }
}

void writeRanking(std::ostream& out, const GapReport& r) {
  out << "## Ranking (held-out data)\n\n";
  if (r.ranking.empty()) {
    out << "No candidate was fitted.\n\n";
    return;
  }
  out << "| # | effect | form | fitted parameters (± 1σ, SI) | gap before | gap after | shrink | score |\n";
  out << "|---:|---|---|---|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < r.ranking.size(); ++i) {
    const RankedEffect& e = r.ranking[i];
    const bool winner = e.effect == r.verdict.effect;
    const std::string name = cell(e.effect) + (e.closed_loop_bounded ? "" : " (closed loop unbounded)") +
                             (e.implausible.empty() ? "" : " (implausible magnitude)");
    out << "| " << i + 1 << " | " << (winner ? "**" + name + "**" : name) << " | " << cell(e.form.empty() ? "-" : e.form)
        << " | " << cell(paramsWithSigma(e)) << " | " << num(e.heldout_gap_before) << " | " << num(e.heldout_gap_after) << " | "
        << percent(e.shrink) << " | " << num(e.score, "%.3g") << " |\n";
  }
  out << "\nshrink = 1 − gap after / gap before, on held-out data. \"closed loop unbounded\": the fitted effect "
         "makes the closed loop of a training log leave the logged bounds, so it cannot be the cause.";
  std::string unchecked;
  for (const RankedEffect& e : r.ranking) {
    if (!e.closed_loop_checked) unchecked += (unchecked.empty() ? "" : ", ") + e.effect;
  }
  if (!unchecked.empty()) {
    out << " Closed loops not checked (their boundedness could not change the verdict, or the logs cannot drive "
           "one): "
        << cell(unchecked) << ".";
  }
  out << "\n\n";
}

void writeWhere(std::ostream& out, const GapReport& r) {
  const GapWhere& w = r.where;
  out << "## Where\n\n";
  out << "Subsystem carrying the gap: **" << (w.subsystem.empty() ? std::string("n/a") : w.subsystem) << "**\n\n";
  if (!w.subsystems.empty()) {
    out << "Open-loop replay with logged inputs, normalised residual:\n\n";
    out << "| subsystem | nrmse | noise floor | outputs |\n|---|---:|---:|---|\n";
    for (const SubsystemGap& s : w.subsystems) {
      out << "| " << (s.name == w.subsystem ? "**" + cell(s.name) + "**" : cell(s.name)) << " | " << num(s.nrmse)
          << " | " << num(s.noise_floor) << " | " << cell(join(s.outputs, ", ")) << " |\n";
    }
    out << "\n";
  }
  if (!w.windows.empty()) {
    // Seconds since each log's first sample: a log stamped in epoch time (t ~ 1.7e9 s) read 1.692e+09 here.
    out << "Time windows carrying most of the residual energy (seconds since the log's first sample):\n\n"
           "| log | from [s] | to [s] | share |\n|---|---:|---:|---:|\n";
    std::map<std::string, double> starts;
    for (std::size_t i = 0; i < w.windows.size() && i < kWindowsShown; ++i) {
      const WindowShare& s = w.windows[i];
      auto since = [&](double t) { return num(std::round(100.0 * (t - s.log_t0)) / 100.0, "%.6g"); };  // to 10 ms
      out << "| " << cell(s.log) << " | " << since(s.t0) << " | " << since(s.t1) << " | " << percent(s.share) << " |\n";
      if (s.log_t0 != 0.0) starts[s.log] = s.log_t0;
    }
    if (w.windows.size() > kWindowsShown)
      out << "\n(" << w.windows.size() - kWindowsShown << " more windows in report.json)\n";
    for (const auto& [log, t0] : starts) out << "\n" << log << " starts at t = " << num(t0, "%.3f") << " s in its own time.\n";
    out << "\n";
  }
  if (!w.onsets.empty()) {
    out << "The gap sets in mid-run (before it the nominal model matches the log within noise):";
    for (std::size_t i = 0; i < w.onsets.size(); ++i) {
      const RunOnset& o = w.onsets[i];
      out << (i == 0 ? " " : "; ") << cell(o.log) << " at " << num(std::round(10.0 * (o.t - o.log_t0)) / 10.0, "%.6g")
          << " s after its start";
    }
    out << ".\n\n";
  }
  if (!w.bands.empty()) {
    out << "Frequency bands:\n\n| band [Hz] | share |\n|---|---:|\n";
    for (const BandShare& s : w.bands) out << "| " << num(s.f0) << " – " << num(s.f1) << " | " << percent(s.share) << " |\n";
    out << "\n";
  }
  if (!w.regimes.empty()) {
    out << "Operating regimes (bins of the absolute value, SI units):\n\n";
    out << "| variable | bin | share of residual energy | share of time |\n|---|---|---:|---:|\n";
    for (const RegimeShare& s : w.regimes) {
      out << "| " << cell(s.variable) << " | " << num(s.lo) << " – " << num(s.hi) << " | " << percent(s.share) << " | "
          << percent(s.time_share) << " |\n";
    }
    out << "\n";
  }
}

void writeHowFar(std::ostream& out, const GapReport& r) {
  const ClosedLoopGap& h = r.how_far;
  out << "## How far (held-out data)\n\n";
  if (!h.not_run.empty()) {
    out << "Closed-loop replay gap: not run (" << h.not_run << ")\n\n";
  } else {
    out << "Closed-loop replay gap: " << num(h.before) << " → " << num(h.after) << " (shrink "
        << percent(shrinkOf(h.before, h.after)) << ")";
    if (std::isfinite(h.noise_floor)) {
      out << "; net of the logs' noise (a perfect model leaves " << num(h.noise_floor) << "): " << num(h.net_before)
          << " → " << num(h.net_after) << " (shrink " << percent(shrinkOf(h.net_before, h.net_after)) << ")";
    }
    out << "\n\n";
  }
  std::vector<std::string> names;
  for (const auto& [name, value] : h.subsystems_before) names.push_back(name);
  for (const auto& [name, value] : h.subsystems_after)
    if (!h.subsystems_before.count(name)) names.push_back(name);
  if (names.empty()) return;
  out << "Per subsystem: the excess of the replay residual over its white-noise floor, and the excess the same\n"
         "replay shows on the noise-only reference (the nominal loop with this log's noise: what a perfect model\n"
         "leaves). The gap counts sqrt(excess² − reference²).\n\n";
  out << "| subsystem | excess before | excess after | noise reference | shrink (net of reference) |\n"
         "|---|---:|---:|---:|---:|\n";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto net = [](double excess, double reference) {
    return std::sqrt(std::max(0.0, excess * excess - reference * reference));
  };
  for (const std::string& name : names) {
    const auto b = h.subsystems_before.find(name);
    const auto a = h.subsystems_after.find(name);
    const auto n = h.subsystems_noise_reference.find(name);
    const double before = b == h.subsystems_before.end() ? nan : b->second;
    const double after = a == h.subsystems_after.end() ? nan : a->second;
    const double reference = n == h.subsystems_noise_reference.end() ? 0.0 : n->second;
    out << "| " << cell(name) << " | " << num(before) << " | " << num(after) << " | " << num(reference) << " | "
        << percent(shrinkOf(net(before, reference), net(after, reference))) << " |\n";
  }
  out << "\n";
}

void writeInputChecks(std::ostream& out, const GapReport& r) {
  out << "## Input checks\n\n";
  if (r.input_checks.empty()) {
    out << "Nothing odd found in the logs (holes, stuck channels, sample rates, units, speed; docs/gap.md, "
           "\"Inputs\").\n\n";
    return;
  }
  for (const InputCheckEntry& c : r.input_checks) {
    out << "- " << c.log << ", " << c.channel << " (" << c.kind << "): " << c.detail << "\n";
  }
  out << "\n";
}

void writeData(std::ostream& out, const GapReport& r) {
  out << "## Data\n\n";
  out << "- training logs: " << (r.logs.empty() ? "none listed" : join(r.logs, ", ")) << "\n";
  out << "- held-out: " << (r.heldout.empty() ? "none listed" : join(r.heldout, ", ")) << "\n";
  out << "- rows used: " << r.rows_used << "; rows skipped (NaN/Inf/empty cells): " << r.rows_skipped << "\n";
  if (!r.notes.empty()) {
    out << "\nNotes:\n\n";
    for (const std::string& note : r.notes) out << "- " << note << "\n";
  }
  if (!r.wall_seconds.empty()) {
    out << "\nWall time per stage:";
    for (const auto& [stage, seconds] : r.wall_seconds) out << " " << stage << " " << num(seconds, "%.1f") << " s;";
    out << "\n";
  }
  out << "\n";
}

void writePlots(std::ostream& out, const std::string& dir, const std::string& shown_dir) {
  static const std::vector<std::pair<std::string, std::string>> plots{
      {"residuals.png", "Normalised residual per subsystem against time (top windows shaded)"},
      {"spectrum.png", "Residual spectra and band shares"},
      {"overlay.png", "Held-out closed-loop replay: real vs nominal vs corrected"},
      {"ranking.png", "Held-out gap before/after per candidate effect"}};
  std::vector<const std::pair<std::string, std::string>*> present;
  std::error_code ec;
  for (const auto& p : plots)
    if (fs::is_regular_file(fs::path(dir) / p.first, ec)) present.push_back(&p);
  out << "## Plots\n\n";
  if (present.empty()) {
    out << "No plots (run `/usr/bin/python3 scripts/gap_report_plots.py " << shown_dir << "`).\n";
    return;
  }
  for (const auto* p : present) out << "### " << p->second << "\n\n![" << p->second << "](" << p->first << ")\n\n";
}

}  // namespace

void writeGapReportMarkdown(const std::string& dir, const GapReport& report, const std::string& shown_dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir + ": cannot create report directory: " + ec.message());
  const std::string path = (fs::path(dir) / "report.md").string();

  std::ostringstream out;
  out << "# Sim-to-real gap report\n\n";
  writeVerdict(out, report);
  writeInputChecks(out, report);
  writeRanking(out, report);
  writeWhere(out, report);
  writeHowFar(out, report);
  writeData(out, report);
  writePlots(out, dir, shown_dir.empty() ? dir : shown_dir);

  std::ofstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open for writing");
  file << out.str();
  file.flush();
  if (!file) throw InputError(path + ": write failed");
}

}  // namespace lane_keeping
