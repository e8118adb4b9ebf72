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
    if (size_ > 0 && stamp <= back().stamp) {
      throw InputError(name_ + ": sample stamped " + std::to_string(stamp) + " ns is not newer than the last one (" +
                       std::to_string(back().stamp) + " ns)");
    }
    if (size_ == ring_.size()) grow();
    ring_[(head_ + size_) & mask_] = Stamped<S>{stamp, value};
    ++size_;
  }

  bool empty() const { return size_ == 0; }
  Nanoseconds delay() const { return delay_; }
  Nanoseconds latestStamp() const { return size_ == 0 ? -1 : back().stamp; }
  const std::string& name() const { return name_; }
  std::size_t size() const { return size_; }

  /// True when the value for consumer time t is final.
  bool covers(Nanoseconds t) const {
    if (size_ == 0) return false;
    const Nanoseconds query = t - delay_;
    const Nanoseconds latest = back().stamp;
    if (query <= latest) return true;
    return hold_ == Hold::kZeroOrder && latest + producer_period_ > query;
  }

  /// The value for consumer time t. Throws ScheduleError if not covers(t).
  S at(Nanoseconds t) const {
    if (!covers(t)) {
      throw ScheduleError(name_ + ": value for t = " + std::to_string(t) + " ns needs a sample stamped " +
                          std::to_string(t - delay_) + " ns, latest is " + std::to_string(latestStamp()) + " ns");
    }
    const Nanoseconds query = t - delay_;
    if (query <= item(0).stamp) return item(0).value;
    // Consumers prune what they have read (discardBefore), so the samples around the query sit at
    // the front even when the producer runs far ahead (the tracker, by tau1): scan from the front.
    std::size_t i = 0;
    while (i + 1 < size_ && item(i + 1).stamp <= query) ++i;  // last stamp <= query
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
    const Nanoseconds query = t - delay_;
    while (size_ >= 2 && item(1).stamp <= query) {
      head_ = (head_ + 1) & mask_;
      --size_;
    }
  }

 private:
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

  std::string name_;
  Nanoseconds delay_;
  Hold hold_;
  Nanoseconds producer_period_;
  std::vector<Stamped<S>> ring_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::size_t mask_ = 0;
};

}  // namespace lane_keeping
