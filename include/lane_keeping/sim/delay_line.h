#pragma once
/// Transport delay keyed by timestamps (DESIGN §4), never by ticks.
///
/// A sample stamped t (the instant the quantity refers to) is used from consumer time t + delay
/// on. The consumer reads the value at t_q = t - delay:
///  * before the first sample: the first sample's value (constant initial history, as for a DDE);
///  * `linear`: linear interpolation between the samples around t_q;
///  * `zoh`: the latest sample stamped <= t_q (zero-order hold).
/// A read is *covered* (final, whatever arrives later) once a sample stamped >= t_q is in, or —
/// for zoh — once the producer's next sample (latest stamp + producer period) lies beyond t_q.
/// Lockstep scheduling rests on coverage: a component computes its output for time t as soon as
/// every input line covers t.
///
/// Stamps are integer nanoseconds and the interpolation weight is computed from them, so the
/// in-process runner and the ROS nodes read bit-identical values.
///
/// A delay that changes during a run (runtime tuning, change_schedule.h) is a right-continuous step
/// function of the consumer's time: tau(t) = tau_0 before the first change, tau_i from its time t_i
/// on, and the value for time t is the input at t - tau(t). A longer delay therefore re-reads older
/// input (the output repeats a stretch of its input), a shorter one skips ahead (a stretch is never
/// read); coverage and interpolation are those above with tau(t) in place of tau. Reads that go back
/// in time need the older samples: the line keeps what every known future delay needs, and, for
/// changes not known in advance, what a delay up to retainFor()'s bound needs.
#include <algorithm>
#include <vector>
#include <stdexcept>
#include <string>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/time.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

enum class Hold { kLinear, kZeroOrder };

inline Hold holdFromName(const std::string& name) {
  if (name == "linear") return Hold::kLinear;
  if (name == "zoh") return Hold::kZeroOrder;
  throw ConfigError("delays.hold = '" + name + "' is unknown; allowed: linear, zoh");
}

template <typename S>
class DelayLine {
 public:
  /// @param delay transport delay [ns] >= 0; @param producer_period the producer's sample period [ns].
  DelayLine(std::string name, Nanoseconds delay, Hold hold, Nanoseconds producer_period)
      : name_(std::move(name)), delay_(delay), hold_(hold), producer_period_(producer_period) {
    if (delay < 0) throw ConfigError(name_ + ": negative delay");
  }

  /// Appends a sample. Stamps must increase strictly; a repeated or older stamp throws InputError
  /// (the ROS wrappers turn that into a warning and drop the message).
  void push(Nanoseconds stamp, const S& value) {
    if (size_ > 0 && stamp <= back().stamp) throwNotNewer(stamp);
    if (size_ == ring_.size()) grow();
    ring_[(head_ + size_) & mask_] = Stamped<S>{stamp, value};
    ++size_;
  }

  bool empty() const { return size_ == 0; }
  /// The delay in force at the latest time discardBefore() was called with (the initial one before).
  Nanoseconds delay() const { return delay_; }
  /// The delay for consumer time t [ns]: the last change at or before t, else the current delay.
  Nanoseconds delayAt(Nanoseconds t) const {
    if (changes_.empty()) return delay_;  // the common case: no change of the delay scheduled
    for (std::size_t i = changes_.size(); i-- > 0;) {
      if (changes_[i].from <= t) return changes_[i].delay;
    }
    return delay_;
  }
  /// From consumer time `from` [ns] on, the delay is `delay` [ns]; a later call for the same time
  /// wins. `from` must not precede a time already read (the consumer's next time or later).
  void scheduleDelay(Nanoseconds from, Nanoseconds delay) {
    if (delay < 0) throw ConfigError(name_ + ": negative delay");
    const auto at = std::upper_bound(changes_.begin(), changes_.end(), from,
                                     [](Nanoseconds t, const DelayChange& c) { return t < c.from; });
    changes_.insert(at, DelayChange{from, delay});
  }
  /// Forgets the delay changes scheduled at `from` [ns] or later (before they are scheduled again).
  void clearDelaysFrom(Nanoseconds from) {
    changes_.erase(std::remove_if(changes_.begin(), changes_.end(),
                                  [from](const DelayChange& c) { return c.from >= from; }),
                   changes_.end());
  }
  /// Keeps the input history a delay up to `max_delay` [ns] needs, for delay changes not known in
  /// advance (0, the default: only what the current and the scheduled delays need).
  void retainFor(Nanoseconds max_delay) { retention_ = max_delay; }
  Nanoseconds latestStamp() const { return size_ == 0 ? -1 : back().stamp; }
  const std::string& name() const { return name_; }
  std::size_t size() const { return size_; }

  /// True when the value for consumer time t is final.
  bool covers(Nanoseconds t) const { return coversQuery(t - delayAt(t)); }

  /// The value for consumer time t. Throws ScheduleError if not covers(t).
  S at(Nanoseconds t) const {
    const Nanoseconds query = t - delayAt(t);
    if (!coversQuery(query)) throwNotCovered(t);
    if (query <= item(0).stamp) return item(0).value;
    // Consumers prune what they have read (discardBefore), so the samples around the query usually
    // sit at the front even when the producer runs far ahead (the tracker, by tau1). With a retained
    // history (retainFor, or a longer delay to come) they sit further in, near the newest sample (a
    // consumer reads as soon as its input covers the read): look there first, then binary search.
    std::size_t i = 0;  // last stamp <= query
    if (size_ >= 2 && item(1).stamp <= query) {
      std::size_t hi = size_ - 1;
      for (int steps = 0; hi > 1 && item(hi).stamp > query && steps < 4; ++steps) --hi;
      std::size_t lo = item(hi).stamp <= query ? hi : 1;
      if (lo != hi) --hi;  // the answer lies in [1, hi]
      while (lo < hi) {
        const std::size_t mid = lo + (hi - lo + 1) / 2;
        if (item(mid).stamp <= query) {
          lo = mid;
        } else {
          hi = mid - 1;
        }
      }
      i = lo;
    }
    if (item(i).stamp == query || hold_ == Hold::kZeroOrder || i + 1 == size_) {
      return item(i).value;
    }
    const Stamped<S>& a = item(i);
    const Stamped<S>& b = item(i + 1);
    const double w = static_cast<double>(query - a.stamp) / static_cast<double>(b.stamp - a.stamp);
    return S::interpolate(a.value, b.value, w);
  }

  /// Drops samples no read at consumer time >= t can need (keeps the one at or before t - delay).
  void discardBefore(Nanoseconds t) {
    // Keep the sample at or before t - d for d the longest delay a read at t or later may use: the
    // delay at t, every delay scheduled after t, and the retained bound. Changes at or before t
    // become the current delay (no read comes before t any more).
    Nanoseconds longest = delay_;
    if (!changes_.empty()) {
      std::size_t passed = 0;
      while (passed < changes_.size() && changes_[passed].from <= t) delay_ = changes_[passed++].delay;
      changes_.erase(changes_.begin(), changes_.begin() + static_cast<std::ptrdiff_t>(passed));
      longest = delay_;
      for (const DelayChange& c : changes_) longest = std::max(longest, c.delay);
    }
    longest = std::max(longest, retention_);
    const Nanoseconds query = t - longest;
    while (size_ >= 2 && item(1).stamp <= query) {
      head_ = (head_ + 1) & mask_;
      --size_;
    }
  }

 private:
  /// covers() for the input time t - tau(t).
  bool coversQuery(Nanoseconds query) const {
    if (size_ == 0) return false;
    const Nanoseconds latest = back().stamp;
    if (query <= latest) return true;
    return hold_ == Hold::kZeroOrder && latest + producer_period_ > query;
  }
  // The errors are built out of line: with the message's string arithmetic inline, every read and push
  // (several per plant step) paid a large stack frame and saved registers on the way in.
  [[gnu::noinline, gnu::cold]] void throwNotNewer(Nanoseconds stamp) const {
    throw InputError(name_ + ": sample stamped " + std::to_string(stamp) + " ns is not newer than the last one (" +
                     std::to_string(back().stamp) + " ns)");
  }
  [[gnu::noinline, gnu::cold]] void throwNotCovered(Nanoseconds t) const {
    throw ScheduleError(name_ + ": value for t = " + std::to_string(t) + " ns needs a sample stamped " +
                        std::to_string(t - delayAt(t)) + " ns, latest is " + std::to_string(latestStamp()) + " ns");
  }

  // Ring buffer with a power-of-two capacity: pushes and discards never allocate once it has grown
  // to the producer's lead.
  const Stamped<S>& item(std::size_t i) const { return ring_[(head_ + i) & mask_]; }
  const Stamped<S>& back() const { return item(size_ - 1); }
  void grow() {
    std::vector<Stamped<S>> bigger(ring_.empty() ? 16 : 2 * ring_.size());
    for (std::size_t i = 0; i < size_; ++i) bigger[i] = item(i);
    ring_.swap(bigger);
    head_ = 0;
    mask_ = ring_.size() - 1;
  }

  struct DelayChange {
    Nanoseconds from;   ///< consumer time [ns] from which it holds
    Nanoseconds delay;  ///< [ns]
  };

  std::string name_;
  Nanoseconds delay_;
  std::vector<DelayChange> changes_;  // by `from`; after discardBefore(t), all later than t
  Nanoseconds retention_ = 0;
  Hold hold_;
  Nanoseconds producer_period_;
  std::vector<Stamped<S>> ring_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::size_t mask_ = 0;
};

}  // namespace lane_keeping
