// report.json of the gap diagnosis (DESIGN §5), written and read with nlohmann/json.
//
// Layout (keys in this order; every GapReport field appears):
//   { "format": "lane_keeping.gap_report", "version": 1,
//     "logs": [..], "heldout": [..], "logs_t0": {log: first sample [s]}, "rows_used": N, "rows_skipped": N,
//     "notes": [..], "skipped_subsystems": [{"name", "reason"}], "not_testable": [{"effect", "reason"}], "not_fitted": [..],
//     "input_checks": [{"log", "channel", "kind", "detail", "t0", "t1" (a hole's; only for holes)}],
//     "split": { "method", "coverage": {kind: held-out share} },
//     "detection": { "draws", "false_alarm_rate", "heldout": {"tested", "value", "p_value", "null_median",
//                    "null_max", "detected"}, "training": {..}, "pooled": {..} (both sides together) }
//                  (not tested: p_value null, no "detected"),
//     "folds": [{"training": [..], "heldout": [..], "effect", "form", "basis", "heldout_p", "gap_before", "gap_after",
//                "params": {}}] (both folds, where the verdict was decided on the pooled test or every fold was
//                asked for; each run held out in turn, with three runs or more; else empty),
//     "where":   { "subsystem", "subsystems": [{"name", "nrmse", "noise_floor", "outputs": [..]}],
//                  "windows": [{"log", "t0", "t1", "share", "log_t0"}], "onset" (optional),
//                  "onsets": [{"log", "t", "since_start"}] (per run; since_start = t - the log's first sample),
//                  "bands": [{"f0", "f1", "share"}],
//                  "regimes": [{"variable", "lo", "hi", "share", "time_share"}] },
//     "ranking": [{"effect", "form", "params": {}, "param_sigma": {}, "config": {"key": "value"},
//                  "train_gap_before", "train_gap_after", "heldout_gap_before", "heldout_gap_after",
//                  "shrink", "score", "closed_loop_bounded", "closed_loop_checked", "implausible" (only where it is)}],
//     "verdict": { "effect", "form", "confidence", "gap_before", "gap_after", "shrink", "reason",
//                  "basis" ("replays", "modal": named on the loop's modes, modal_evidence.h, "targeted": a delay named on its own fit against the draws' same fit, targeted_test.h, or "measured": a sensor error the input checks measured, decision/measured_sensor_errors.h), "confusable_with": [..],
//                  "effects": [{"effect", "form", "params": {}, "param_sigma": {}, ["replay_params": {}], "config": {}, "share", "gap_after",
//                               "evidence", "sensor", "measured" (only where true), "confusable_with": [..]}], "combined_gap_after", "combined_shrink",
//                  "partial": {"effect", "form", "share", "untouched_share", "whiteness_p", "input_correlation_p"}
//                  (only when a candidate explains part of the gap) },
//     "how_far": { "before", "after", "shrink", "noise_floor", "net_before", "net_after", "net_shrink" (the closed-loop
//                  gaps net of the logs' noise, how_far.h), "not_run" (why, only when the closed loop was not replayed:
//                  before and after are null then), "subsystems_before": {}, "subsystems_after": {},
//                  "subsystems_noise_reference": {} },
//     "wall_seconds": [{"stage", "seconds"}] }
// how_far.shrink = 1 - after / before and net_shrink = 1 - net_after / net_before are derived (written for
// readers, ignored when read back).
// Non-finite numbers (NaN, +-Inf) are written as JSON null (JSON has no NaN) and read back as NaN,
// so an infinite value does not survive a round trip.
#include "lane_keeping/gap/report/gap_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

using OrderedJson = nlohmann::ordered_json;
using Json = nlohmann::json;
namespace fs = std::filesystem;

constexpr const char* kFormat = "lane_keeping.gap_report";
constexpr int kVersion = 1;

OrderedJson number(double v) { return std::isfinite(v) ? OrderedJson(v) : OrderedJson(nullptr); }

OrderedJson numberMap(const std::map<std::string, double>& m) {
  OrderedJson out = OrderedJson::object();
  for (const auto& [key, value] : m) out[key] = number(value);
  return out;
}

OrderedJson toJson(const GapWhere& w) {
  OrderedJson out;
  out["subsystem"] = w.subsystem;
  out["subsystems"] = OrderedJson::array();
  for (const SubsystemGap& s : w.subsystems) {
    out["subsystems"].push_back(
        {{"name", s.name}, {"nrmse", number(s.nrmse)}, {"noise_floor", number(s.noise_floor)}, {"outputs", s.outputs}});
  }
  out["windows"] = OrderedJson::array();
  for (const WindowShare& s : w.windows)
    out["windows"].push_back({{"log", s.log},
                              {"t0", number(s.t0)},
                              {"t1", number(s.t1)},
                              {"share", number(s.share)},
                              {"log_t0", number(s.log_t0)}});
  if (std::isfinite(w.onset)) out["onset"] = w.onset;
  out["onsets"] = OrderedJson::array();
  for (const RunOnset& o : w.onsets) {
    out["onsets"].push_back({{"log", o.log}, {"t", number(o.t)}, {"since_start", number(o.t - o.log_t0)}});
  }
  out["bands"] = OrderedJson::array();
  for (const BandShare& s : w.bands)
    out["bands"].push_back({{"f0", number(s.f0)}, {"f1", number(s.f1)}, {"share", number(s.share)}});
  out["regimes"] = OrderedJson::array();
  for (const RegimeShare& s : w.regimes) {
    out["regimes"].push_back({{"variable", s.variable},
                              {"lo", number(s.lo)},
                              {"hi", number(s.hi)},
                              {"share", number(s.share)},
                              {"time_share", number(s.time_share)}});
  }
  return out;
}

OrderedJson toJson(const RankedEffect& r) {
  OrderedJson out;
  out["effect"] = r.effect;
  out["form"] = r.form;
  out["params"] = numberMap(r.params);
  out["param_sigma"] = numberMap(r.param_sigma);
  out["config"] = OrderedJson::object();
  for (const auto& [key, value] : r.config) out["config"][key] = value;
  out["train_gap_before"] = number(r.train_gap_before);
  out["train_gap_after"] = number(r.train_gap_after);
  out["heldout_gap_before"] = number(r.heldout_gap_before);
  out["heldout_gap_after"] = number(r.heldout_gap_after);
  out["shrink"] = number(r.shrink);
  out["score"] = number(r.score);
  out["closed_loop_bounded"] = r.closed_loop_bounded;
  if (!r.implausible.empty()) out["implausible"] = r.implausible;  // only where it is: earlier reports stay as they were
  out["closed_loop_checked"] = r.closed_loop_checked;
  return out;
}

OrderedJson toJson(const PartialExplanation& p) {
  OrderedJson out;
  out["effect"] = p.effect;
  out["form"] = p.form;
  out["share"] = number(p.share);
  out["untouched_share"] = number(p.untouched_share);
  out["whiteness_p"] = number(p.whiteness_p);
  out["input_correlation_p"] = number(p.input_correlation_p);
  return out;
}

OrderedJson toJson(const DetectionTest& d) {
  // Without noise-only draws there is no test: no p-value and no "detected", but "tested": false.
  if (!d.tested) {
    return OrderedJson{{"tested", false}, {"value", number(d.value)}, {"p_value", nullptr},
                       {"null_median", nullptr}, {"null_max", nullptr}};
  }
  return OrderedJson{{"tested", true},
                     {"value", number(d.value)},          {"p_value", number(d.p_value)},
                     {"null_median", number(d.null_median)}, {"null_max", number(d.null_max)},
                     {"detected", d.detected}};
}

OrderedJson toJson(const GapVerdict& v) {
  OrderedJson out;
  out["effect"] = v.effect;
  out["form"] = v.form;
  out["confidence"] = number(v.confidence);
  out["gap_before"] = number(v.gap_before);
  out["gap_after"] = number(v.gap_after);
  out["shrink"] = number(v.shrink);
  out["reason"] = v.reason;
  out["basis"] = v.basis;
  out["confusable_with"] = v.confusable_with;
  out["effects"] = OrderedJson::array();
  for (const VerdictEffect& e : v.effects) {
    OrderedJson j;
    j["effect"] = e.effect;
    j["form"] = e.form;
    j["params"] = numberMap(e.params);
    j["param_sigma"] = numberMap(e.param_sigma);
    if (!e.replay_params.empty()) j["replay_params"] = numberMap(e.replay_params);  // only where placed
    j["config"] = e.config;
    j["share"] = number(e.share);
    j["gap_after"] = number(e.gap_after);
    j["evidence"] = number(e.evidence);
    j["sensor"] = e.sensor;
    if (e.measured) j["measured"] = true;  // only where true: earlier reports stay as they were
    j["confusable_with"] = e.confusable_with;
    out["effects"].push_back(j);
  }
  out["combined_gap_after"] = number(v.combined_gap_after);
  out["combined_shrink"] = number(v.combined_shrink);
  if (!v.partial.effect.empty()) out["partial"] = toJson(v.partial);
  return out;
}

OrderedJson toJson(const ClosedLoopGap& h) {
  OrderedJson out;
  out["before"] = number(h.before);
  out["after"] = number(h.after);
  out["shrink"] = (std::isfinite(h.before) && h.before > 0.0) ? number(1.0 - h.after / h.before) : OrderedJson(nullptr);
  if (!h.not_run.empty()) out["not_run"] = h.not_run;
  out["noise_floor"] = number(h.noise_floor);
  out["net_before"] = number(h.net_before);
  out["net_after"] = number(h.net_after);
  out["net_shrink"] =
      (std::isfinite(h.net_before) && h.net_before > 0.0) ? number(1.0 - h.net_after / h.net_before) : OrderedJson(nullptr);
  out["subsystems_before"] = numberMap(h.subsystems_before);
  out["subsystems_after"] = numberMap(h.subsystems_after);
  out["subsystems_noise_reference"] = numberMap(h.subsystems_noise_reference);
  return out;
}

OrderedJson toJson(const GapReport& r) {
  OrderedJson out;
  out["format"] = kFormat;
  out["version"] = kVersion;
  out["logs"] = r.logs;
  out["heldout"] = r.heldout;
  out["logs_t0"] = numberMap(r.logs_t0);
  out["rows_used"] = r.rows_used;
  out["rows_skipped"] = r.rows_skipped;
  out["notes"] = r.notes;
  out["skipped_subsystems"] = OrderedJson::array();
  for (const auto& s : r.skipped_subsystems) out["skipped_subsystems"].push_back({{"name", s.name}, {"reason", s.reason}});
  out["not_testable"] = OrderedJson::array();
  for (const auto& e : r.not_testable) out["not_testable"].push_back({{"effect", e.effect}, {"reason", e.reason}});
  out["input_checks"] = OrderedJson::array();
  for (const auto& c : r.input_checks) {
    OrderedJson entry{{"log", c.log}, {"channel", c.channel}, {"kind", c.kind}, {"detail", c.detail}};
    if (c.kind == "hole") {
      entry["t0"] = number(c.t0);
      entry["t1"] = number(c.t1);
    }
    out["input_checks"].push_back(entry);
  }
  out["not_fitted"] = OrderedJson::array();
  for (const auto& e : r.not_fitted) out["not_fitted"].push_back({{"effect", e.effect}, {"reason", e.reason}});
  out["split"] = OrderedJson{{"method", r.split.method}, {"coverage", numberMap(r.split.coverage)}};
  out["detection"] = OrderedJson{{"draws", r.detection.draws},
                                 {"false_alarm_rate", number(r.detection.false_alarm_rate)},
                                 {"heldout", toJson(r.detection.heldout)},
                                 {"training", toJson(r.detection.training)},
                                 {"pooled", toJson(r.detection.pooled)}};
  out["folds"] = OrderedJson::array();
  for (const GapFold& f : r.folds) {
    out["folds"].push_back(OrderedJson{{"training", f.training},
                                       {"heldout", f.heldout},
                                       {"effect", f.effect},
                                       {"form", f.form},
                                       {"basis", f.basis},
                                       {"heldout_p", number(f.heldout_p)},
                                       {"gap_before", number(f.gap_before)},
                                       {"gap_after", number(f.gap_after)},
                                       {"params", numberMap(f.params)}});
  }
  out["where"] = toJson(r.where);
  out["ranking"] = OrderedJson::array();
  for (const RankedEffect& e : r.ranking) out["ranking"].push_back(toJson(e));
  out["verdict"] = toJson(r.verdict);
  out["how_far"] = toJson(r.how_far);
  out["wall_seconds"] = OrderedJson::array();
  for (const auto& [stage, seconds] : r.wall_seconds) {
    out["wall_seconds"].push_back(OrderedJson{{"stage", stage}, {"seconds", number(seconds)}});
  }
  return out;
}

/// A directory argument means DIR/report.json.
std::string resolvePath(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return (fs::path(path) / "report.json").string();
  return path;
}

// ---- reading: every access names the JSON path on error -------------------------------------

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(file_ + ": " + where + ": " + what);
  }

  /// Member `key` of object `j` (at JSON path `where`); nullptr if absent and not required.
  const Json* member(const Json& j, const std::string& where, const std::string& key, bool required) const {
    if (!j.is_object()) fail(where, "expected an object");
    const auto it = j.find(key);
    if (it == j.end()) {
      if (required) fail(where + "." + key, "missing");
      return nullptr;
    }
    return &*it;
  }

  double toDouble(const Json& j, const std::string& where) const {
    if (j.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!j.is_number()) fail(where, "expected a number or null, found " + std::string(j.type_name()));
    return j.get<double>();
  }
  std::string toString(const Json& j, const std::string& where) const {
    if (!j.is_string()) fail(where, "expected a string, found " + std::string(j.type_name()));
    return j.get<std::string>();
  }

  void get(const Json& j, const std::string& where, const std::string& key, double* out, bool required = false) const {
    if (const Json* m = member(j, where, key, required)) *out = toDouble(*m, where + "." + key);
  }
  void get(const Json& j, const std::string& where, const std::string& key, bool* out, bool required = false) const {
    const Json* m = member(j, where, key, required);
    if (!m) return;
    if (!m->is_boolean()) fail(where + "." + key, "expected true or false, found " + m->dump());
    *out = m->get<bool>();
  }
  void get(const Json& j, const std::string& where, const std::string& key, std::string* out,
           bool required = false) const {
    if (const Json* m = member(j, where, key, required)) *out = toString(*m, where + "." + key);
  }
  void get(const Json& j, const std::string& where, const std::string& key, std::size_t* out,
           bool required = false) const {
    const Json* m = member(j, where, key, required);
    if (!m) return;
    if (!m->is_number_unsigned() && !(m->is_number_integer() && m->get<long long>() >= 0))
      fail(where + "." + key, "expected a non-negative integer, found " + m->dump());
    *out = m->get<std::size_t>();
  }
  void get(const Json& j, const std::string& where, const std::string& key, std::vector<std::string>* out,
           bool required = false) const {
    const Json* m = member(j, where, key, required);
    if (!m) return;
    if (!m->is_array()) fail(where + "." + key, "expected an array of strings");
    out->clear();
    for (std::size_t i = 0; i < m->size(); ++i)
      out->push_back(toString((*m)[i], where + "." + key + "[" + std::to_string(i) + "]"));
  }
  void get(const Json& j, const std::string& where, const std::string& key, std::map<std::string, double>* out,
           bool required = false) const {
    const Json* m = member(j, where, key, required);
    if (!m) return;
    if (!m->is_object()) fail(where + "." + key, "expected an object of numbers");
    out->clear();
    for (const auto& [name, value] : m->items()) (*out)[name] = toDouble(value, where + "." + key + "." + name);
  }
  void get(const Json& j, const std::string& where, const std::string& key, std::map<std::string, std::string>* out,
           bool required = false) const {
    const Json* m = member(j, where, key, required);
    if (!m) return;
    if (!m->is_object()) fail(where + "." + key, "expected an object of strings");
    out->clear();
    for (const auto& [name, value] : m->items()) (*out)[name] = toString(value, where + "." + key + "." + name);
  }

  /// Calls f(element, path) for each element of array `key`.
  template <typename F>
  void forEach(const Json& j, const std::string& where, const std::string& key, bool required, F f) const {
    const Json* m = member(j, where, key, required);
    if (!m) return;
    if (!m->is_array()) fail(where + "." + key, "expected an array");
    for (std::size_t i = 0; i < m->size(); ++i) f((*m)[i], where + "." + key + "[" + std::to_string(i) + "]");
  }

 private:
  std::string file_;
};

}  // namespace

const std::vector<std::string>& candidateEffectNames() {
  static const std::vector<std::string> names{
      "tire_lag",         "sensing_delay",     "actuation_delay",     "steering_friction",
      "torque_limit",     "road_friction",     "cornering_stiffness", "lateral_disturbance",
      "pose_bias",        "steering_compliance", "inertia",             "sensor_offset",
      "sensor_scale",     "sensor_latency"};
  return names;
}

std::string gapReportJson(const GapReport& report) { return toJson(report).dump(2) + "\n"; }

std::string closedLoopGapJson(const ClosedLoopGap& how_far) { return toJson(how_far).dump(); }

void writeGapReportJson(const std::string& path_or_dir, const GapReport& report) {
  const std::string path = resolvePath(path_or_dir);
  const std::string text = gapReportJson(report);
  // Write to a temporary file and rename, so a reader never sees half a report.
  const std::string temp = path + ".tmp";
  {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw InputError(path + ": cannot open for writing (does the directory exist and is it writable?)");
    out << text;
    out.flush();
    if (!out) throw InputError(temp + ": write failed");
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw InputError(path + ": cannot write: " + ec.message());
  }
}

GapReport readGapReportJson(const std::string& path_or_dir) {
  const std::string path = resolvePath(path_or_dir);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open report");
  Json j;
  try {
    j = Json::parse(in);
  } catch (const Json::exception& e) {  // parse_error, and out_of_range for a number beyond double's range
    throw InputError(path + ": not valid JSON: " + e.what());
  }
  const Reader r(path);
  const std::string root = "$";
  if (!j.is_object()) r.fail(root, "expected an object");

  GapReport rep;
  r.get(j, root, "logs", &rep.logs);
  r.get(j, root, "heldout", &rep.heldout);
  r.get(j, root, "logs_t0", &rep.logs_t0);
  r.get(j, root, "rows_used", &rep.rows_used);
  r.get(j, root, "rows_skipped", &rep.rows_skipped);
  r.get(j, root, "notes", &rep.notes);
  r.forEach(j, root, "skipped_subsystems", false, [&](const Json& e, const std::string& p) {
    SkippedSubsystem s;
    r.get(e, p, "name", &s.name, true);
    r.get(e, p, "reason", &s.reason);
    rep.skipped_subsystems.push_back(s);
  });
  r.forEach(j, root, "not_testable", false, [&](const Json& e, const std::string& p) {
    UntestableEffect u;
    r.get(e, p, "effect", &u.effect, true);
    r.get(e, p, "reason", &u.reason);
    rep.not_testable.push_back(u);
  });
  r.forEach(j, root, "input_checks", false, [&](const Json& e, const std::string& p) {
    InputCheckEntry c;
    r.get(e, p, "log", &c.log);
    r.get(e, p, "channel", &c.channel);
    r.get(e, p, "kind", &c.kind, true);
    r.get(e, p, "detail", &c.detail);
    r.get(e, p, "t0", &c.t0);
    r.get(e, p, "t1", &c.t1);
    rep.input_checks.push_back(c);
  });
  r.forEach(j, root, "not_fitted", false, [&](const Json& e, const std::string& p) {
    UntestableEffect u;
    r.get(e, p, "effect", &u.effect, true);
    r.get(e, p, "reason", &u.reason);
    rep.not_fitted.push_back(u);
  });
  if (const Json* s = r.member(j, root, "split", false)) {
    r.get(*s, root + ".split", "method", &rep.split.method);
    r.get(*s, root + ".split", "coverage", &rep.split.coverage);
  }
  if (const Json* d = r.member(j, root, "detection", false)) {
    const std::string dp = root + ".detection";
    std::size_t draws = 0;
    r.get(*d, dp, "draws", &draws);
    rep.detection.draws = static_cast<int>(draws);
    r.get(*d, dp, "false_alarm_rate", &rep.detection.false_alarm_rate);
    for (auto [key, test] : {std::pair<const char*, DetectionTest*>{"heldout", &rep.detection.heldout},
                             std::pair<const char*, DetectionTest*>{"training", &rep.detection.training},
                             std::pair<const char*, DetectionTest*>{"pooled", &rep.detection.pooled}}) {
      if (const Json* e = r.member(*d, dp, key, false)) {
        const std::string ep = dp + "." + key;
        r.get(*e, ep, "tested", &test->tested);  // absent in older reports: tested
        r.get(*e, ep, "value", &test->value);
        r.get(*e, ep, "p_value", &test->p_value);
        r.get(*e, ep, "null_median", &test->null_median);
        r.get(*e, ep, "null_max", &test->null_max);
        r.get(*e, ep, "detected", &test->detected);
      }
    }
  }
  r.forEach(j, root, "folds", false, [&](const Json& e, const std::string& p) {  // absent in older reports
    GapFold f;
    r.get(e, p, "training", &f.training);
    r.get(e, p, "heldout", &f.heldout);
    r.get(e, p, "effect", &f.effect, true);
    r.get(e, p, "form", &f.form);
    r.get(e, p, "basis", &f.basis);
    r.get(e, p, "heldout_p", &f.heldout_p);
    r.get(e, p, "gap_before", &f.gap_before);
    r.get(e, p, "gap_after", &f.gap_after);
    r.get(e, p, "params", &f.params);
    rep.folds.push_back(f);
  });

  // DESIGN §5 keys are required; the others are optional (defaults when absent).
  const std::string wp = root + ".where";
  const Json& w = *r.member(j, root, "where", true);
  r.get(w, wp, "subsystem", &rep.where.subsystem, true);
  r.forEach(w, wp, "subsystems", true, [&](const Json& e, const std::string& p) {
    SubsystemGap s;
    r.get(e, p, "name", &s.name, true);
    r.get(e, p, "nrmse", &s.nrmse, true);
    r.get(e, p, "noise_floor", &s.noise_floor);
    r.get(e, p, "outputs", &s.outputs);
    rep.where.subsystems.push_back(s);
  });
  r.forEach(w, wp, "windows", true, [&](const Json& e, const std::string& p) {
    WindowShare s;
    r.get(e, p, "log", &s.log);
    r.get(e, p, "t0", &s.t0, true);
    r.get(e, p, "t1", &s.t1, true);
    r.get(e, p, "share", &s.share, true);
    r.get(e, p, "log_t0", &s.log_t0);
    rep.where.windows.push_back(s);
  });
  r.get(w, wp, "onset", &rep.where.onset);
  r.forEach(w, wp, "onsets", false, [&](const Json& e, const std::string& p) {
    RunOnset o;
    double since_start = 0.0;
    r.get(e, p, "log", &o.log, true);
    r.get(e, p, "t", &o.t, true);
    r.get(e, p, "since_start", &since_start, true);
    o.log_t0 = o.t - since_start;
    rep.where.onsets.push_back(o);
  });
  r.forEach(w, wp, "bands", true, [&](const Json& e, const std::string& p) {
    BandShare s;
    r.get(e, p, "f0", &s.f0, true);
    r.get(e, p, "f1", &s.f1, true);
    r.get(e, p, "share", &s.share, true);
    rep.where.bands.push_back(s);
  });
  r.forEach(w, wp, "regimes", false, [&](const Json& e, const std::string& p) {
    RegimeShare s;
    r.get(e, p, "variable", &s.variable, true);
    r.get(e, p, "lo", &s.lo);
    r.get(e, p, "hi", &s.hi);
    r.get(e, p, "share", &s.share);
    r.get(e, p, "time_share", &s.time_share);
    rep.where.regimes.push_back(s);
  });

  r.forEach(j, root, "ranking", true, [&](const Json& e, const std::string& p) {
    RankedEffect s;
    r.get(e, p, "effect", &s.effect, true);
    r.get(e, p, "form", &s.form);
    r.get(e, p, "params", &s.params, true);
    r.get(e, p, "param_sigma", &s.param_sigma);
    r.get(e, p, "config", &s.config);
    r.get(e, p, "train_gap_before", &s.train_gap_before);
    r.get(e, p, "train_gap_after", &s.train_gap_after);
    r.get(e, p, "heldout_gap_before", &s.heldout_gap_before, true);
    r.get(e, p, "heldout_gap_after", &s.heldout_gap_after, true);
    r.get(e, p, "shrink", &s.shrink, true);
    r.get(e, p, "score", &s.score);
    r.get(e, p, "closed_loop_bounded", &s.closed_loop_bounded);
    r.get(e, p, "implausible", &s.implausible);  // absent: plausible
    r.get(e, p, "closed_loop_checked", &s.closed_loop_checked);  // absent in older reports: read as checked
    rep.ranking.push_back(s);
  });

  const std::string vp = root + ".verdict";
  const Json& v = *r.member(j, root, "verdict", true);
  r.get(v, vp, "effect", &rep.verdict.effect, true);
  r.get(v, vp, "form", &rep.verdict.form);
  r.get(v, vp, "confidence", &rep.verdict.confidence, true);
  r.get(v, vp, "gap_before", &rep.verdict.gap_before, true);
  r.get(v, vp, "gap_after", &rep.verdict.gap_after, true);
  r.get(v, vp, "shrink", &rep.verdict.shrink, true);
  r.get(v, vp, "reason", &rep.verdict.reason);
  r.get(v, vp, "basis", &rep.verdict.basis);  // absent in older reports: "replays"
  r.get(v, vp, "confusable_with", &rep.verdict.confusable_with);
  r.forEach(v, vp, "effects", false, [&](const Json& e, const std::string& p) {  // absent in older reports
    VerdictEffect s;
    r.get(e, p, "effect", &s.effect, true);
    r.get(e, p, "form", &s.form);
    r.get(e, p, "params", &s.params);
    r.get(e, p, "param_sigma", &s.param_sigma);
    r.get(e, p, "replay_params", &s.replay_params);  // absent: not placed
    r.get(e, p, "config", &s.config);
    r.get(e, p, "share", &s.share);
    r.get(e, p, "gap_after", &s.gap_after);
    r.get(e, p, "evidence", &s.evidence);
    r.get(e, p, "sensor", &s.sensor);
    r.get(e, p, "measured", &s.measured);  // absent: fitted
    r.get(e, p, "confusable_with", &s.confusable_with);
    rep.verdict.effects.push_back(s);
  });
  r.get(v, vp, "combined_gap_after", &rep.verdict.combined_gap_after);
  r.get(v, vp, "combined_shrink", &rep.verdict.combined_shrink);
  if (const Json* partial = r.member(v, vp, "partial", false)) {
    const std::string pp = vp + ".partial";
    PartialExplanation& px = rep.verdict.partial;
    r.get(*partial, pp, "effect", &px.effect, true);
    r.get(*partial, pp, "form", &px.form);
    r.get(*partial, pp, "share", &px.share);
    r.get(*partial, pp, "untouched_share", &px.untouched_share);
    r.get(*partial, pp, "whiteness_p", &px.whiteness_p);
    r.get(*partial, pp, "input_correlation_p", &px.input_correlation_p);
  }

  if (const Json* h = r.member(j, root, "how_far", false)) {
    const std::string hp = root + ".how_far";
    r.get(*h, hp, "before", &rep.how_far.before);
    r.get(*h, hp, "after", &rep.how_far.after);
    r.get(*h, hp, "not_run", &rep.how_far.not_run);
    r.get(*h, hp, "noise_floor", &rep.how_far.noise_floor);  // absent in older reports: NaN
    r.get(*h, hp, "net_before", &rep.how_far.net_before);
    r.get(*h, hp, "net_after", &rep.how_far.net_after);
    r.get(*h, hp, "subsystems_before", &rep.how_far.subsystems_before);
    r.get(*h, hp, "subsystems_after", &rep.how_far.subsystems_after);
    r.get(*h, hp, "subsystems_noise_reference", &rep.how_far.subsystems_noise_reference);
  }
  r.forEach(j, root, "wall_seconds", false, [&](const Json& e, const std::string& p) {
    std::pair<std::string, double> stage;
    r.get(e, p, "stage", &stage.first, true);
    r.get(e, p, "seconds", &stage.second, true);
    rep.wall_seconds.push_back(stage);
  });
  return rep;
}

}  // namespace lane_keeping
