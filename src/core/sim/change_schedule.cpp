#include "lane_keeping/sim/change_schedule.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/config_assignments.h"
#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/loop_components.h"
#include "lane_keeping/sim/model_factory.h"

namespace lane_keeping {
namespace {

bool isDelayKey(const std::string& key) { return key.rfind("delays.", 0) == 0; }

/// The first multiple of `period` at or after t (grids start at 0).
Nanoseconds snapToGrid(Nanoseconds t, Nanoseconds period) { return ((t + period - 1) / period) * period; }

std::string stateLayout(const SingleTrackModel& model) {
  std::ostringstream out;
  out << model.stateSize() << " states: " << static_cast<int>(kRigidStateSize) << " rigid";
  const SteeringParams& s = model.steering();
  if (s.compliant()) out << ", 2 compliant column";
  if (s.lugreFriction()) out << ", 1 LuGre kingpin friction";
  out << ", " << model.frontTire().stateSize() << " front tire (" << model.frontTire().name() << "), "
      << model.rearTire().stateSize() << " rear tire (" << model.rearTire().name() << ")";
  return out.str();
}

/// "= v" for the first of `keys`, then " (with k2 = v2, ...)" for the others.
std::string valuesText(const std::vector<std::pair<std::string, std::string>>& keys_values) {
  std::string text = "= " + keys_values.front().second;
  for (std::size_t i = 1; i < keys_values.size(); ++i) {
    text += (i == 1 ? " (with " : ", ") + keys_values[i].first + " = " + keys_values[i].second;
    if (i + 1 == keys_values.size()) text += ")";
  }
  return text;
}

std::string requestText(double t, const std::vector<std::pair<std::string, std::string>>& assignments) {
  std::string text;
  for (const auto& [key, value] : assignments) {
    text += (text.empty() ? "" : ", ") + TimedChange{t, key, value}.text();
  }
  return text;
}

[[noreturn]] void refuse(const std::string& key, const std::string& location, const std::string& message) {
  throw ConfigError(std::vector<ConfigProblem>{{key, location, message}});
}

}  // namespace

std::string ScheduledChange::argument() const {
  return formatNumber(nanosecondsToSeconds(stamp)) + ":" + key + "=" + new_value;
}

std::string ScheduledChange::describe() const {
  return "t = " + formatNumber(nanosecondsToSeconds(stamp)) + " s: " + key + " " + old_value + " -> " + new_value +
         " (" + roleName(owner) + ")";
}

void sortForSummary(std::vector<ScheduledChange>& changes) {
  std::stable_sort(changes.begin(), changes.end(), [](const ScheduledChange& a, const ScheduledChange& b) {
    return a.stamp != b.stamp ? a.stamp < b.stamp : a.key < b.key;
  });
}

ChangeSchedule::ChangeSchedule(SimConfig initial) : initial_(std::move(initial)) {}

Nanoseconds ChangeSchedule::gridOf(LoopRole role) const {
  const LoopSchedule grids = loopScheduleOf(initial_);
  switch (role) {
    case LoopRole::kTracker:
      return grids.tracker_period;
    case LoopRole::kActuator:
      return grids.actuator_period;
    case LoopRole::kPlant:
      return grids.plant_step;
  }
  return grids.plant_step;
}

void ChangeSchedule::addAll(const std::vector<TimedChange>& list, const std::string& origin) {
  // A change after the run's end would never take effect: it was dropped without a word.
  const double end = initial_.simulation.duration;
  for (const TimedChange& change : list) {
    if (change.t > end) {
      refuse(change.key, origin + " '" + change.text() + "'",
             "at t = " + formatNumber(change.t) + " s is after the run's end (simulation.duration = " +
                 formatNumber(end) + " s): it would never take effect");
    }
  }
  // Equal times are one request: their keys are checked together (both tau2 delays, say, which one
  // at a time could leave a schedule that stalls in between).
  std::vector<TimedChange> sorted = list;
  std::stable_sort(sorted.begin(), sorted.end(), [](const TimedChange& a, const TimedChange& b) { return a.t < b.t; });
  for (std::size_t i = 0; i < sorted.size();) {
    std::vector<std::pair<std::string, std::string>> group;
    std::size_t j = i;
    for (; j < sorted.size() && sorted[j].t == sorted[i].t; ++j) {
      // One key twice at one time: the later value won and both were reported as changes to it.
      for (std::size_t k = i; k < j; ++k) {
        if (sorted[k].key == sorted[j].key) {
          refuse(sorted[j].key, origin + " '" + sorted[j].text() + "'",
                 "is changed twice at t = " + formatNumber(sorted[j].t) + " s ('" + sorted[k].text() + "' and '" +
                     sorted[j].text() + "'): give one value");
        }
      }
      group.emplace_back(sorted[j].key, sorted[j].value);
    }
    add(sorted[i].t, group, origin);
    i = j;
  }
}

void ChangeSchedule::checkEntryGroup(const SimConfig& before, const SimConfig& after,
                                     const std::vector<const Entry*>& group) const {
  bool plant_mid_run = false, delays = false;
  for (const Entry* e : group) {
    plant_mid_run = plant_mid_run || (e->change.owner == LoopRole::kPlant && e->change.stamp > 0);
    delays = delays || isDelayKey(e->change.key);
  }
  // The keys concerned, the first named as the problem's key and the others beside its value.
  auto concerned = [&](bool (*which)(const Entry&)) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const Entry* g : group) {
      if (which(*g)) out.emplace_back(g->change.key, g->change.new_value);
    }
    return out;
  };
  if (plant_mid_run) {
    // The state carries over a change, so it must mean the same thing before and after.
    const std::string was = stateLayout(createVehicleModel(before));
    const std::string now = stateLayout(createVehicleModel(after));
    if (was != now) {
      const auto keys = concerned([](const Entry& e) { return e.change.owner == LoopRole::kPlant; });
      refuse(keys.front().first, group.front()->change.origin,
             valuesText(keys) + " changes the plant model's state (" + was + " -> " + now +
                 "); the state carries over a change during a run, so this can change only at t = 0 (or in the "
                 "configuration)");
    }
  }
  if (delays) {
    try {
      checkLockstepFeasible(after);
    } catch (const ScheduleError& e) {
      const auto keys = concerned([](const Entry& e) { return isDelayKey(e.change.key); });
      refuse(keys.front().first, group.front()->change.origin,
             valuesText(keys) + " s leaves a loop that cannot run in lockstep: " + e.what());
    }
  }
}

void ChangeSchedule::recheck(std::vector<Entry>& entries, std::size_t first) const {
  for (std::size_t i = first; i < entries.size();) {
    std::size_t j = i;
    std::vector<std::string> assignments;
    std::vector<const Entry*> group;
    for (; j < entries.size() && entries[j].group == entries[i].group; ++j) {
      assignments.push_back(entries[j].assignment);
      group.push_back(&entries[j]);
    }
    const SimConfig& before = i == 0 ? initial_ : *entries[i - 1].after;
    auto after = std::make_shared<const SimConfig>(withAssignments(before, assignments, entries[i].change.origin));
    checkEntryGroup(before, *after, group);
    for (std::size_t k = i; k < j; ++k) entries[k].after = after;
    i = j;
  }
}

std::vector<ScheduledChange> ChangeSchedule::add(double t,
                                                 const std::vector<std::pair<std::string, std::string>>& assignments,
                                                 const std::string& origin, Nanoseconds earliest) {
  if (assignments.empty()) return {};
  const std::string location = origin + " '" + requestText(t, assignments) + "'";
  if (!std::isfinite(t) || t < 0.0 || t > kMaxChangeTime) {
    refuse(assignments.front().first, location,
           "time " + formatNumber(t) + " s must be in [0, " + formatNumber(kMaxChangeTime) + "] s");
  }
  const Nanoseconds requested = std::max(secondsToNanoseconds(t), earliest);
  const auto position = std::upper_bound(entries_.begin(), entries_.end(), requested,
                                         [](Nanoseconds r, const Entry& e) { return r < e.order; });
  const std::size_t pos = static_cast<std::size_t>(position - entries_.begin());
  const SimConfig& before = pos == 0 ? initial_ : *entries_[pos - 1].after;

  // The reader and validate() of a configuration file, on the configuration in force then.
  std::vector<std::string> texts;
  for (const auto& [key, value] : assignments) texts.push_back(key + "=" + value);
  auto after = std::make_shared<const SimConfig>(withAssignments(before, texts, location));

  std::vector<Entry> group;
  for (std::size_t i = 0; i < assignments.size(); ++i) {
    const std::string& key = assignments[i].first;
    Entry e;
    e.change.key = key;
    try {
      e.change.owner = changeOwner(key);
    } catch (const ConfigError& error) {  // a key fixed for a run: say which request named it
      refuse(key, location, error.problems().front().message);
    }
    e.change.stamp = snapToGrid(requested, gridOf(e.change.owner));
    e.change.old_value = configValueText(before, key);
    e.change.new_value = configValueText(*after, key);
    e.change.origin = location;
    e.after = after;
    e.order = requested;
    e.group = next_group_;
    e.assignment = texts[i];
    group.push_back(std::move(e));
  }
  // A later change of the same key was recorded with the value before it as its old value; putting
  // one in between would falsify that record.
  for (std::size_t k = pos; k < entries_.size(); ++k) {
    for (const Entry& e : group) {
      if (entries_[k].change.key == e.change.key) {
        refuse(e.change.key, location,
               "has a change scheduled later, at t = " + formatNumber(nanosecondsToSeconds(entries_[k].change.stamp)) +
                   " s (" + entries_[k].change.origin + "); a change before it cannot be added");
      }
    }
  }
  std::vector<const Entry*> pointers;
  for (const Entry& e : group) pointers.push_back(&e);
  checkEntryGroup(before, *after, pointers);

  std::vector<Entry> updated = entries_;
  updated.insert(updated.begin() + static_cast<std::ptrdiff_t>(pos), group.begin(), group.end());
  try {
    recheck(updated, pos + group.size());
  } catch (const ConfigError& e) {
    refuse(group.front().change.key, location, "conflicts with a change scheduled after it: " + std::string(e.what()));
  }
  entries_ = std::move(updated);
  ++next_group_;
  std::vector<ScheduledChange> records;
  for (const Entry& e : group) records.push_back(e.change);
  return records;
}

std::vector<ScheduledChange> ChangeSchedule::changes() const {
  std::vector<ScheduledChange> out;
  for (const Entry& e : entries_) out.push_back(e.change);
  return out;
}

const SimConfig& ChangeSchedule::start() const {
  const SimConfig* config = &initial_;
  for (const Entry& e : entries_) {
    if (e.change.stamp != 0) break;
    config = e.after.get();
  }
  return *config;
}

const SimConfig& ChangeSchedule::configFor(LoopRole role, Nanoseconds t) const {
  for (std::size_t i = entries_.size(); i-- > 0;) {
    const Entry& e = entries_[i];
    if (e.change.owner == role && e.change.stamp <= t) return *e.after;
  }
  return start();
}

}  // namespace lane_keeping
