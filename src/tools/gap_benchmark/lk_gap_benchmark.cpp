// lk_gap_benchmark: the withheld-effect benchmark of the gap diagnosis.
//   lk_gap_benchmark run      --out DIR [--family F] [--cases SUBSTRING] [--threads N] [--coarse-fit-stride K]
//                              generate + diagnose + score (K: DiagnosisOptions::coarse_fit_stride)
//   lk_gap_benchmark generate --out DIR [--family F] [--cases SUBSTRING] [--log-rate HZ] [--noise-seed K]
//     F: candidates (default: the family written beside the candidates) or independent (docs/gap.md)
//     K: every case's noise drawn afresh (its seed + K; 0, the default: the family as written), the same
//        effects, roads and set-ups: how much of a verdict is its noise draw's
//   lk_gap_benchmark diagnose --dir DIR [--cases SUBSTRING] [--threads N] [--coarse-fit-stride K]
//   lk_gap_benchmark ceiling  --dir DIR [--cases SUBSTRING] [--threads N]
//   lk_gap_benchmark score    --dir DIR
// `generate` writes DIR/logs/<case>.csv, DIR/nominal/<manoeuvre>.yaml, DIR/cases.json (case id,
// manoeuvre, log file, and a held-out run's log and scenario (DIR/scenarios/) where the case has one on
// another road: no truth) and DIR/truth.json (the hidden effects). `diagnose` reads only
// cases.json, the logs and the nominal configurations, and writes DIR/reports/<case>/report.json.
// `ceiling` (after the diagnosis, with the truth) scores each log's truth configuration as the
// diagnosis scores a candidate and writes DIR/reports/<case>/ceiling.json: the shrink a perfect
// candidate would reach, which replay limits and noise keep below 100 %, and its closed-loop how far (net of
// the logs' noise, as a verdict's is measured). `score` compares the verdicts
// with truth.json and prints the confusion matrix, top-1 accuracy, median held-out shrink when right
// (and the truth model's, where `ceiling` ran), false alarms on no-effect logs and the out-of-list
// verdicts; then, for the independent family's groups (independent_groups.h), one table per group:
// top-1 (effect, and its form where the case sets one: a sensor error's channel), several effects at
// once (the verdict one of them, all named in verdict.effects), no-effect and out-of-list logs
// `unexplained`, the median held-out and closed-loop (how far) shrinks when right, and each log; last,
// the whole family against its targets (printOverall).
// Exit status (usage()): 0 ok, 2 bad arguments, 4 bad input data, 1 other error.
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lane_keeping/common/command_line.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/median.h"
#include "lane_keeping/config/param_readers.h"
#include "gap_benchmark/benchmark_cases.h"
#include "gap_benchmark/independent_groups.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/report/gap_report.h"

using namespace lane_keeping;
using nlohmann::json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void makeDir(const std::string& path) { ::mkdir(path.c_str(), 0755); }


json readJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open (a directory lk_gap_benchmark generate wrote?)");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path + ": not valid JSON: " + e.what());
  }
}

void writeJson(const std::string& path, const json& j) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write");
  out << j.dump(2) << "\n";
}

std::vector<BenchmarkCase> selectCases(const std::string& family, const std::string& filter) {
  std::vector<BenchmarkCase> out;
  for (const auto& c : familyCases(family)) {
    if (filter.empty() || c.id.find(filter) != std::string::npos) out.push_back(c);
  }
  return out;
}

/// A case as truth.json holds it (caseFromTruth reads it back).
json truthJson(const BenchmarkCase& c) {
  json j{{"id", c.id},         {"category", c.category},    {"truth", c.truth}, {"magnitude", c.magnitude},
         {"manoeuvre", c.manoeuvre}, {"overlay", c.truth_overlay}, {"seed", c.seed}, {"setup", c.setup},
         {"log_rate", c.log_rate},   {"noise_scale", c.noise_scale}};
  // The fields of the groups (benchmark_cases.h), written only where a case has them.
  if (!c.group.empty()) j["group"] = c.group;
  if (!c.truth_form.empty()) j["truth_form"] = c.truth_form;
  if (!c.truths.empty()) {
    j["truths"] = json::array();
    for (const auto& t : c.truths) j["truths"].push_back({{"effect", t.effect}, {"form", t.form}});
  }
  if (!c.sensor_character.empty()) {
    json characters = json::object();
    for (const auto& [column, ch] : c.sensor_character) {
      characters[column] = {{"quantum", ch.quantum}, {"offset", ch.offset}, {"hold", ch.hold}, {"ar", ch.ar},
                            {"sigma", ch.sigma}};
    }
    j["sensor_character"] = characters;
  }
  return j;
}

BenchmarkCase caseFromTruth(const json& t) {
  BenchmarkCase c;
  c.id = t["id"];
  c.category = t["category"];
  c.truth = t["truth"];
  c.magnitude = t["magnitude"];
  c.manoeuvre = t["manoeuvre"];
  c.truth_overlay = t["overlay"].get<std::vector<std::string>>();
  c.seed = t["seed"];
  if (t.contains("setup")) c.setup = t["setup"].get<std::vector<std::string>>();
  if (t.contains("log_rate")) c.log_rate = t["log_rate"];
  if (t.contains("noise_scale")) c.noise_scale = t["noise_scale"];
  c.group = t.value("group", std::string());
  c.truth_form = t.value("truth_form", std::string());
  if (t.contains("truths")) {
    for (const auto& e : t["truths"]) c.truths.push_back({e["effect"].get<std::string>(), e.value("form", std::string())});
  }
  if (t.contains("sensor_character")) {
    for (const auto& [column, ch] : t["sensor_character"].items()) {
      ChannelCharacter character;
      character.quantum = ch.value("quantum", 0.0);
      character.offset = ch.value("offset", 0.0);
      character.hold = ch.value("hold", 1);
      character.ar = ch.value("ar", 0.0);
      character.sigma = ch.value("sigma", 0.0);
      c.sensor_character[column] = character;
    }
  }
  return c;
}

/// The nominal configuration file of a case (cases.json's "nominal"; the manoeuvre's for older
/// directories).
std::string nominalFile(const std::string& dir, const json& c) {
  return dir + "/" + (c.contains("nominal") ? c["nominal"].get<std::string>() : "nominal/" + c["manoeuvre"].get<std::string>() + ".yaml");
}

void generate(const std::string& dir, const std::string& family, const std::string& filter, double log_rate,
              unsigned noise_seed) {
  makeDir(dir);
  makeDir(dir + "/logs");
  makeDir(dir + "/nominal");
  json cases = json::array(), truth = json::array();
  for (const std::string m : {"lane_change", "sinusoid"}) {
    std::ofstream out(dir + "/nominal/" + m + ".yaml");
    out << "# nominal configuration of the gap benchmark, manoeuvre " << m << "\n";
    benchmarkNominal(m).print(out);
  }
  for (BenchmarkCase c : selectCases(family, filter)) {
    c.seed += noise_seed;  // the held-out run's and the further runs' seeds follow from it
    const auto start = std::chrono::steady_clock::now();
    const GapLog log = generateBenchmarkLog(c, SensorNoise{}, log_rate);
    const std::string file = "logs/" + c.id + ".csv";
    writeCsvLog(dir + "/" + file, log);
    json entry{{"id", c.id}, {"manoeuvre", c.manoeuvre}, {"log", file}};
    if (!c.setup.empty()) {  // a set-up of its own: the diagnosis is given its own nominal
      const std::string nominal = "nominal/" + c.id + ".yaml";
      std::ofstream out(dir + "/" + nominal);
      out << "# nominal configuration of the gap benchmark case " << c.id << "\n";
      benchmarkCaseNominal(c).print(out);
      entry["nominal"] = nominal;
    }
    if (!c.heldout_manoeuvre.empty()) {  // a held-out run on another road, with its scenario
      makeDir(dir + "/scenarios");
      const BenchmarkCase h = heldoutRunOf(c);
      const std::string heldout_log = "logs/" + h.id + ".csv", scenario = "scenarios/" + h.id + ".yaml";
      writeCsvLog(dir + "/" + heldout_log, generateBenchmarkLog(h, SensorNoise{}, log_rate));
      std::ofstream(dir + "/" + scenario) << benchmarkScenarioYaml(h);
      entry["heldout"] = {{"log", heldout_log}, {"scenario", scenario}};
    }
    for (std::size_t k = 0; k < c.more_runs.size(); ++k) {  // further training runs, each with its scenario
      makeDir(dir + "/scenarios");
      const BenchmarkCase r = moreRunOf(c, k);
      const std::string run_log = "logs/" + r.id + ".csv", scenario = "scenarios/" + r.id + ".yaml";
      writeCsvLog(dir + "/" + run_log, generateBenchmarkLog(r, SensorNoise{}, log_rate));
      std::ofstream(dir + "/" + scenario) << benchmarkScenarioYaml(r);
      entry["more_runs"].push_back({{"log", run_log}, {"scenario", scenario}});
    }
    cases.push_back(entry);
    truth.push_back(truthJson(c));
    std::fprintf(stderr, "[generate] %-44s %5zu rows  %.1f s\n", c.id.c_str(), log.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  writeJson(dir + "/cases.json", cases);
  writeJson(dir + "/truth.json", truth);
}

/// The training and held-out runs of a case as lk_gap builds them: the log under the case's nominal, its
/// further runs with their scenarios and, where the case has one, the held-out log with its own scenario.
std::pair<std::vector<GapRun>, std::vector<GapRun>> caseRuns(const std::string& dir, const json& c) {
  FlatParams nominal;
  nominal.overlayFile(nominalFile(dir, c));
  std::vector<GapRun> training, heldout;
  training.push_back(gapRun(readCsvLog(dir + "/" + c["log"].get<std::string>()), nominal, FlatParams{}, ""));
  if (c.contains("more_runs")) {
    for (const auto& run : c["more_runs"]) {
      training.push_back(gapRun(readCsvLog(dir + "/" + run["log"].get<std::string>()), nominal,
                                dir + "/" + run["scenario"].get<std::string>()));
    }
  }
  if (c.contains("heldout")) {
    heldout.push_back(gapRun(readCsvLog(dir + "/" + c["heldout"]["log"].get<std::string>()), nominal,
                             dir + "/" + c["heldout"]["scenario"].get<std::string>()));
  }
  return {std::move(training), std::move(heldout)};
}

void diagnose(const std::string& dir, const std::string& filter, int threads, std::size_t coarse_fit_stride) {
  makeDir(dir + "/reports");
  const json cases = readJson(dir + "/cases.json");  // no truth in here
  for (const auto& c : cases) {
    const std::string id = c["id"];
    if (!filter.empty() && id.find(filter) == std::string::npos) continue;
    const auto start = std::chrono::steady_clock::now();
    const SimConfig nominal = loadSimConfig({nominalFile(dir, c)});
    const auto [training, heldout] = caseRuns(dir, c);
    DiagnosisOptions options;
    options.threads = threads;
    options.coarse_fit_stride = coarse_fit_stride;
    const GapReport report = diagnoseGap(nominal, training, heldout, options);
    makeDir(dir + "/reports/" + id);
    writeGapReportJson(dir + "/reports/" + id + "/report.json", report);
    std::fprintf(stderr, "[diagnose] %-44s -> %-20s conf %.2f shrink %5.1f %%  %.1f s\n", id.c_str(),
                 report.verdict.effect.c_str(), report.verdict.confidence, 100.0 * report.verdict.shrink,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
}

void ceiling(const std::string& dir, const std::string& filter, int threads) {
  const json truth = readJson(dir + "/truth.json");
  const json cases = readJson(dir + "/cases.json");
  std::map<std::string, json> case_entries;
  for (const auto& c : cases) case_entries[c["id"]] = c;
  for (const auto& t : truth) {
    const BenchmarkCase c = caseFromTruth(t);
    if ((!filter.empty() && c.id.find(filter) == std::string::npos) || c.category == "none") continue;
    const auto start = std::chrono::steady_clock::now();
    const auto [training, heldout] = caseRuns(dir, case_entries.at(c.id));
    DiagnosisOptions options;
    options.threads = threads;
    const ConfigChange truth_change = assignmentsChange(c.truth_overlay);
    const std::vector<double> gaps = heldoutGaps(training, heldout, {truth_change}, options);
    const double shrink = gaps[0] > 0.0 ? 1.0 - gaps[1] / gaps[0] : 0.0;
    // And in closed loop, as how_far measures a verdict: what a perfect verdict's simulation would close.
    // report.json's how_far object, by its writer: its net_shrink is the truth model's how far.
    const json closed = json::parse(closedLoopGapJson(closedLoopHowFar(training, heldout, truth_change, options)));
    makeDir(dir + "/reports/" + c.id);
    writeJson(dir + "/reports/" + c.id + "/ceiling.json",
              {{"gap_before", gaps[0]}, {"truth_gap_after", gaps[1]}, {"truth_shrink", shrink}, {"how_far", closed}});
    const double net = closed["net_shrink"].is_number() ? closed["net_shrink"].get<double>() : kNaN;
    std::fprintf(stderr, "[ceiling]  %-44s truth model shrink %6.1f %%, how far %6.1f %% net  %.1f s\n", c.id.c_str(),
                 100.0 * shrink, 100.0 * net, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
}

/// The truth model's shrink on a log (ceiling.json), or NaN if `ceiling` has not run.
double truthShrink(const std::string& dir, const std::string& id) {
  std::ifstream in(dir + "/reports/" + id + "/ceiling.json");
  if (!in) return kNaN;
  return json::parse(in)["truth_shrink"].get<double>();
}

/// The truth model's closed-loop shrink net of the logs' noise (ceiling.json's how_far.net_shrink), or NaN where
/// `ceiling` has not run, ran before it measured the closed loop, or the closed loop gave no net gap.
double truthNetHowFar(const std::string& dir, const std::string& id) {
  std::ifstream in(dir + "/reports/" + id + "/ceiling.json");
  if (!in) return kNaN;
  const json ceiling = json::parse(in);
  const auto how_far = ceiling.find("how_far");
  if (how_far == ceiling.end() || !how_far->is_object()) return kNaN;
  const auto net = how_far->find("net_shrink");
  return net == how_far->end() || !net->is_number() ? kNaN : net->get<double>();
}

/// Whether a verdict's form names the truth's: equal to it, or among the forms the logs cannot tell apart
/// ("aerodynamic or road_bank" names both). An empty truth form accepts any.
bool formNames(const std::string& truth_form, const std::string& form) {
  if (truth_form.empty()) return true;
  for (std::size_t begin = 0;;) {
    const std::size_t end = form.find(" or ", begin);
    if (form.substr(begin, end == std::string::npos ? std::string::npos : end - begin) == truth_form) return true;
    if (end == std::string::npos) return false;
    begin = end + 4;
  }
}

bool names(const TruthEffect& truth, const std::string& effect, const std::string& form) {
  return effect == truth.effect && formNames(truth.form, form);
}

std::string label(const std::string& effect, const std::string& form) {
  return form.empty() ? effect : effect + " (" + form + ")";
}

/// A case with its report.
struct ScoredCase {
  BenchmarkCase c;
  GapReport r;
  double truth_net_how_far = kNaN;  ///< the truth model's own (truthNetHowFar), where `ceiling` ran

  /// The verdict names the (one) truth, in its form where the truth has one.
  bool right() const {
    for (const auto& t : c.truthEffects()) {
      if (names(t, r.verdict.effect, r.verdict.form)) return true;
    }
    return false;
  }
  /// Every truth is among verdict.effects.
  bool allNamed() const {
    for (const auto& t : c.truthEffects()) {
      bool found = false;
      for (const auto& e : r.verdict.effects) found = found || names(t, e.effect, e.form);
      if (!found) return false;
    }
    return true;
  }
  /// The held-out shrink of what the verdict names (all its effects when it names several).
  double shrink() const { return r.verdict.effects.size() > 1 ? r.verdict.combined_shrink : r.verdict.shrink; }
  /// The closed-loop replay's shrink (how far), NaN when it did not run.
  double howFarShrink() const {
    return r.how_far.before > 0.0 ? 1.0 - r.how_far.after / r.how_far.before : std::numeric_limits<double>::quiet_NaN();
  }
  /// The same net of the logs' noise (how_far.net_before / net_after; NaN in reports without them).
  double netHowFarShrink() const {
    return r.how_far.net_before > 0.0 ? 1.0 - r.how_far.net_after / r.how_far.net_before
                                      : std::numeric_limits<double>::quiet_NaN();
  }
  std::string verdictLabel() const { return label(r.verdict.effect, r.verdict.form); }
  std::string truthLabel() const {
    std::string out;
    for (const auto& t : c.truthEffects()) out += (out.empty() ? "" : " + ") + label(t.effect, t.form);
    return out;
  }
};

std::string percent(double v) {
  if (!std::isfinite(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f %%", 100.0 * v);
  return text;
}

std::string ratio(int n, int of) { return of == 0 ? "-" : std::to_string(n) + " / " + std::to_string(of); }

/// The confusion matrix of one-effect logs: rows the hidden effect (and none), columns the verdict, the 14
/// candidate names numbered so that the columns stay narrow.
void printConfusion(const std::map<std::string, std::map<std::string, int>>& confusion) {
  std::vector<std::string> labels = candidateEffectNames();
  labels.push_back("unexplained");
  std::printf("Confusion matrix (rows: hidden effect; columns: verdict)\n%-21s", "");
  for (std::size_t j = 0; j < labels.size(); ++j) std::printf(" %3zu", j + 1);
  std::printf("\n");
  std::vector<std::string> rows = candidateEffectNames();
  rows.push_back("none");
  for (const auto& row : rows) {
    std::printf("%-21s", row.c_str());
    const auto r = confusion.find(row);
    for (const auto& col : labels) {
      const int n = r == confusion.end() || !r->second.count(col) ? 0 : r->second.at(col);
      std::printf(" %3s", n ? std::to_string(n).c_str() : ".");
    }
    std::printf("\n");
  }
  std::printf("columns: ");
  for (std::size_t j = 0; j < labels.size(); ++j) std::printf("%zu=%s ", j + 1, labels[j].c_str());
  std::printf("\n\n");
}

/// The family's first table (the cases without a group): what the scorer printed before the groups.
void printFamilyTable(const std::string& dir, const std::vector<ScoredCase>& scored) {
  std::map<std::string, std::map<std::string, int>> confusion;
  int in_list = 0, correct = 0, none = 0, false_alarms = 0, outside = 0, outside_unexplained = 0;
  std::vector<double> shrinks, ceilings, how_far, net_how_far, truth_how_far;
  std::vector<std::string> out_of_list, per_log;
  std::vector<std::string> misses;
  for (const ScoredCase& s : scored) {
    const std::string& id = s.c.id;
    const GapReport& r = s.r;
    // The verdict's form is printed where the truth names one (a sensor error's channel).
    const std::string verdict = s.c.truth_form.empty() ? r.verdict.effect : s.verdictLabel();
    if (s.c.category == "in_list") {
      ++in_list;
      confusion[s.c.truth][r.verdict.effect]++;
      const double ceiling = truthShrink(dir, id);
      char line[256];
      std::snprintf(line, sizeof(line), "  %-40s -> %-20s shrink %5.1f %%  truth model %5.1f %%", id.c_str(),
                    verdict.c_str(), 100.0 * r.verdict.shrink, 100.0 * ceiling);
      per_log.push_back(line);
      if (s.right()) {
        ++correct;
        shrinks.push_back(r.verdict.shrink);
        if (std::isfinite(s.howFarShrink())) how_far.push_back(s.howFarShrink());
        if (std::isfinite(s.netHowFarShrink())) net_how_far.push_back(s.netHowFarShrink());
        if (std::isfinite(ceiling)) ceilings.push_back(ceiling);
        if (std::isfinite(s.truth_net_how_far)) truth_how_far.push_back(s.truth_net_how_far);
      } else {
        misses.push_back(id + " -> " + verdict);
      }
    } else if (s.c.category == "none") {
      ++none;
      confusion["none"][r.verdict.effect]++;
      if (r.verdict.effect != "unexplained") {
        ++false_alarms;
        misses.push_back(id + " -> " + verdict + " (false alarm)");
      }
    } else {
      ++outside;
      if (r.verdict.effect == "unexplained") ++outside_unexplained;
      char line[256];
      std::snprintf(line, sizeof(line), "  %-36s -> %-20s conf %.2f shrink %5.1f %%  where %s", id.c_str(), verdict.c_str(),
                    r.verdict.confidence, 100.0 * r.verdict.shrink, r.where.subsystem.c_str());
      out_of_list.push_back(line);
    }
  }
  printConfusion(confusion);
  std::printf("top-1 accuracy (in-list effects):      %d / %d = %.1f %%   (target >= 90 %%)\n", correct, in_list,
              in_list ? 100.0 * correct / in_list : 0.0);
  std::printf("median held-out shrink when right:     %.1f %%   (target >= 80 %%)\n", 100.0 * median(shrinks));
  if (!ceilings.empty()) {
    std::printf("  the truth model's own, same logs:    %.1f %%   (the ceiling: replay limits and noise)\n",
                100.0 * median(ceilings));
  }
  if (!how_far.empty()) {
    std::printf("median closed-loop shrink when right: %.1f %%, net of the logs' noise %s\n", 100.0 * median(how_far),
                net_how_far.empty() ? "-" : percent(median(net_how_far)).c_str());
    if (!truth_how_far.empty()) {
      std::printf("  the truth model's own, same logs:    %s net   (the ceiling in closed loop: the replay's noise)\n",
                  percent(median(truth_how_far)).c_str());
    }
  }
  std::printf("no-effect logs judged unexplained:     %d / %d = %.1f %%   (target >= 90 %%)\n", none - false_alarms, none,
              none ? 100.0 * (none - false_alarms) / none : 0.0);
  std::printf("out-of-list logs judged unexplained:   %d / %d = %.1f %%   (target >= 80 %%)\n", outside_unexplained, outside,
              outside ? 100.0 * outside_unexplained / outside : 0.0);
  std::printf("\nIn-list logs (verdict, its held-out shrink, the truth model's on the same log):\n");
  for (const auto& line : per_log) std::printf("%s\n", line.c_str());
  std::printf("\nOut-of-list effects:\n");
  for (const auto& line : out_of_list) std::printf("%s\n", line.c_str());
  if (!misses.empty()) {
    std::printf("\nMisses:\n");
    for (const auto& m : misses) std::printf("  %s\n", m.c_str());
  }
}

/// One group's table, as Markdown for docs/gap.md, then each log.
void printGroupTable(const std::string& group, const std::vector<ScoredCase>& scored) {
  int single = 0, single_right = 0, several = 0, one_of = 0, both = 0, none = 0, none_unexplained = 0, outside = 0,
      outside_unexplained = 0;
  std::vector<double> shrinks, how_far, net_how_far, truth_how_far;
  std::vector<std::string> lines;
  for (const ScoredCase& s : scored) {
    const bool right = s.right();
    const bool unexplained = s.r.verdict.effect == "unexplained";
    std::string mark;
    if (s.c.category == "none") {
      ++none;
      none_unexplained += unexplained;
      mark = unexplained ? "ok" : "FALSE ALARM";
    } else if (s.c.category == "out_of_list") {
      ++outside;
      outside_unexplained += unexplained;
      mark = unexplained ? "ok" : "named";
    } else {
      if (s.c.truths.size() > 1) {
        ++several;
        one_of += right;
        both += right && s.allNamed();
        mark = right ? (s.allNamed() ? "both named" : "one of them") : "miss";
      } else {
        ++single;
        single_right += right;
        mark = right ? "right" : "miss";
      }
      if (right) {
        shrinks.push_back(s.shrink());
        if (std::isfinite(s.howFarShrink())) how_far.push_back(s.howFarShrink());
        if (std::isfinite(s.netHowFarShrink())) net_how_far.push_back(s.netHowFarShrink());
        if (std::isfinite(s.truth_net_how_far)) truth_how_far.push_back(s.truth_net_how_far);
      }
    }
    std::string named;
    for (const auto& e : s.r.verdict.effects) named += (named.empty() ? "" : ", ") + label(e.effect, e.form);
    std::string named_text = s.r.verdict.effects.size() > 1 ? "  named: " + named : "";
    if (s.r.folds.size() == 2) {  // decided on the pooled test (fold_pooling.h): what each fold named
      named_text += "  [two folds: " + label(s.r.folds[0].effect, s.r.folds[0].form) + " / " +
                    label(s.r.folds[1].effect, s.r.folds[1].form) + "]";
    }
    const std::string truth_text =
        std::isfinite(s.truth_net_how_far) ? "; the truth model's " + percent(s.truth_net_how_far) : std::string();
    char line[800];
    std::snprintf(line, sizeof(line), "  %-56s %-44s -> %-34s %-12s shrink %s, how far %s (net %s%s)%s", s.c.id.c_str(),
                  s.truthLabel().c_str(), s.verdictLabel().c_str(), mark.c_str(), percent(s.shrink()).c_str(),
                  percent(s.howFarShrink()).c_str(), percent(s.netHowFarShrink()).c_str(), truth_text.c_str(),
                  named_text.c_str());
    lines.push_back(line);
  }
  std::printf("\n=== %s (%zu logs) ===\n\n| | measured |\n|---|---|\n", group.c_str(), scored.size());
  if (single) std::printf("| top-1, one in-list effect (effect, and form where one is set) | %s |\n", ratio(single_right, single).c_str());
  if (several) {
    std::printf("| several effects at once: the verdict is one of them | %s |\n", ratio(one_of, several).c_str());
    std::printf("| several effects at once: all named (verdict.effects) | %s |\n", ratio(both, several).c_str());
  }
  if (none) std::printf("| no-effect logs judged `unexplained` | %s |\n", ratio(none_unexplained, none).c_str());
  if (outside) std::printf("| out-of-list logs judged `unexplained` | %s |\n", ratio(outside_unexplained, outside).c_str());
  if (single + several) {
    std::printf("| median held-out shrink when right | %s |\n", shrinks.empty() ? "-" : percent(median(shrinks)).c_str());
    std::printf("| median closed-loop (how far) shrink when right | %s |\n", how_far.empty() ? "-" : percent(median(how_far)).c_str());
    std::printf("| the same net of the logs' noise | %s |\n", net_how_far.empty() ? "-" : percent(median(net_how_far)).c_str());
    if (!truth_how_far.empty()) {
      std::printf("| the truth model's own on the same logs (`ceiling`, net) | %s |\n", percent(median(truth_how_far)).c_str());
    }
  }
  std::printf("\n");
  for (const auto& line : lines) std::printf("%s\n", line.c_str());
}

/// The whole family against its targets (issue 46 item 7): one in-list effect (all of them, and the
/// sensor errors apart), a sensor error with a physical effect, no-effect and out-of-list logs.
void printOverall(const std::vector<ScoredCase>& all) {
  int single = 0, single_right = 0, sensor = 0, sensor_right = 0, several = 0, one_of = 0, both = 0, none = 0,
      none_unexplained = 0, outside = 0, outside_unexplained = 0;
  for (const ScoredCase& s : all) {
    const bool unexplained = s.r.verdict.effect == "unexplained";
    if (s.c.category == "none") {
      ++none;
      none_unexplained += unexplained;
    } else if (s.c.category == "out_of_list") {
      ++outside;
      outside_unexplained += unexplained;
    } else if (s.c.truthEffects().size() > 1) {
      ++several;
      one_of += s.right();
      both += s.right() && s.allNamed();
    } else {
      ++single;
      single_right += s.right();
      if (isSensorEffect(s.c.truth)) {
        ++sensor;
        sensor_right += s.right();
      }
    }
  }
  auto share = [](int n, int of) { return of ? percent(static_cast<double>(n) / of) : std::string("-"); };
  std::printf("\n=== The whole family (%zu logs) ===\n\n| | measured | target |\n|---|---|---|\n", all.size());
  std::printf("| top-1, one in-list effect | %s = %s | >= 90 %% |\n", ratio(single_right, single).c_str(),
              share(single_right, single).c_str());
  std::printf("| of which sensor errors (effect and channel) | %s = %s | |\n", ratio(sensor_right, sensor).c_str(),
              share(sensor_right, sensor).c_str());
  std::printf("| of which physical effects | %s = %s | |\n", ratio(single_right - sensor_right, single - sensor).c_str(),
              share(single_right - sensor_right, single - sensor).c_str());
  std::printf("| two at once: the verdict is one of them | %s | |\n", ratio(one_of, several).c_str());
  std::printf("| two at once: both named (verdict.effects) | %s | |\n", ratio(both, several).c_str());
  std::printf("| no-effect logs judged `unexplained` | %s = %s | >= 95 %% |\n", ratio(none_unexplained, none).c_str(),
              share(none_unexplained, none).c_str());
  std::printf("| out-of-list logs judged `unexplained` | %s | |\n", ratio(outside_unexplained, outside).c_str());
}

int score(const std::string& dir) {
  const json truth = readJson(dir + "/truth.json");
  std::vector<ScoredCase> family;
  std::map<std::string, std::vector<ScoredCase>> groups;
  std::vector<std::string> group_order = independentGroupNames();
  for (const auto& t : truth) {
    const std::string id = t["id"];
    const std::string path = dir + "/reports/" + id + "/report.json";
    std::ifstream probe(path);
    if (!probe) continue;
    ScoredCase s{caseFromTruth(t), readGapReportJson(path)};
    s.truth_net_how_far = truthNetHowFar(dir, id);
    if (s.c.group.empty()) {
      family.push_back(std::move(s));
    } else {
      if (std::find(group_order.begin(), group_order.end(), s.c.group) == group_order.end()) group_order.push_back(s.c.group);
      groups[s.c.group].push_back(std::move(s));
    }
  }
  if (!family.empty() || groups.empty()) printFamilyTable(dir, family);
  if (groups.empty()) return 0;
  std::printf("\n\nThe groups, each in its own table: right = the verdict names the hidden effect, and "
              "its form where the case sets one; how far = 1 - how_far.after / how_far.before, net = the same of\n"
              "how_far.net_after / how_far.net_before (net of the logs' noise).\n");
  std::map<std::string, std::map<std::string, int>> confusion;
  for (const auto& name : group_order) {
    const auto it = groups.find(name);
    if (it == groups.end()) continue;
    printGroupTable(name, it->second);
    for (const ScoredCase& s : it->second) {
      if (s.c.category == "none") confusion["none"][s.r.verdict.effect]++;
      else if (s.c.category == "in_list" && s.c.truths.size() <= 1) confusion[s.c.truth][s.r.verdict.effect]++;
    }
  }
  std::printf("\nThe groups' one-effect and no-effect logs:\n");
  printConfusion(confusion);
  std::vector<ScoredCase> all = family;
  for (const auto& [name, cases] : groups) all.insert(all.end(), cases.begin(), cases.end());
  printOverall(all);
  return 0;
}

}  // namespace

void usage(std::ostream& out) {
  out << "usage: lk_gap_benchmark run|generate|diagnose|ceiling|score --out/--dir DIR [--family candidates|independent]\n"
         "                        [--cases SUBSTRING] [--threads N] [--coarse-fit-stride K] [--log-rate HZ]\n"
         "                        [--noise-seed K]\n"
         "  run       generate + diagnose + ceiling + score into --out DIR\n"
         "  generate  the logs, cases.json (no truth) and truth.json into --out DIR (--log-rate: rows per second,\n"
         "            default 500, at most the plant's 10,000; --noise-seed K: every case's noise drawn afresh,\n"
         "            its seed + K, the same effects, roads and set-ups)\n"
         "  diagnose, ceiling, score   on --dir DIR, as generate wrote it\n"
         "  --threads N (1-256, default 2), --coarse-fit-stride K (1-1000, default 3)\n"
         "exit status: 0 ok, 2 bad arguments (an unknown command, option or family, a value that is not a number\n"
         "in its range, an option without its value), 4 bad input data (a directory generate did not write),\n"
         "1 other error\n";
}

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    usage(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  std::string dir, filter, family = "candidates";
  int threads = 2;
  std::size_t coarse_fit_stride = DiagnosisOptions{}.coarse_fit_stride;
  double log_rate = 500.0;
  unsigned noise_seed = 0;
  try {
    static const std::set<std::string> commands{"run", "generate", "diagnose", "ceiling", "score"};
    if (!commands.count(command)) throw UsageError("unknown command '" + command + "'");
    for (int i = 2; i < argc; i += 2) {
      const std::string arg = argv[i];
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      const std::string value = argv[i + 1];
      if (arg == "--out" || arg == "--dir") dir = value;
      else if (arg == "--cases") filter = value;
      else if (arg == "--family") family = value;
      else if (arg == "--threads") threads = static_cast<int>(wholeNumberOption(arg, value, 1, 256));
      else if (arg == "--log-rate") log_rate = numberOption(arg, value, 1.0, 1e4, "Hz");
      else if (arg == "--noise-seed") noise_seed = static_cast<unsigned>(wholeNumberOption(arg, value, 0, 1000000));
      else if (arg == "--coarse-fit-stride") coarse_fit_stride = static_cast<std::size_t>(wholeNumberOption(arg, value, 1, 1000));
      else throw UsageError("unknown argument '" + arg + "'");
    }
    if (dir.empty()) throw UsageError("--out/--dir DIR is required");
    familyCases(family);  // an unknown family is a bad argument, before any work
    if (command == "generate" || command == "run") generate(dir, family, filter, log_rate, noise_seed);
    if (command == "diagnose" || command == "run") diagnose(dir, filter, threads, coarse_fit_stride);
    if (command == "ceiling" || command == "run") ceiling(dir, filter, threads);
    if (command == "score" || command == "run") return score(dir);
  } catch (const UsageError& e) {
    std::cerr << "lk_gap_benchmark: " << e.what() << "\n";
    usage(std::cerr);
    return 2;
  } catch (const ConfigError& e) {
    std::cerr << "lk_gap_benchmark: " << e.what() << "\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "lk_gap_benchmark: " << e.what() << "\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "lk_gap_benchmark: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
