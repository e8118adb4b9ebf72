#pragma once
/// What every node does with the loop topics: collect output samples and publish them as one array
/// message per lockstep cycle; check incoming samples and reject bad ones with a warning that
/// names the topic, the sample and the field.
#include <cstdint>
#include <string>

#include <boost/make_shared.hpp>
#include <ros/ros.h>

#include "conversions.h"
#include "lane_keeping/common/errors.h"

namespace lane_keeping {

/// Queue length of the loop topics (publishers and subscribers). A lockstep cycle has at most a
/// few messages in flight, so this never drops one; a dropped loop message would stall the loop.
constexpr std::uint32_t kLoopQueueSize = 10000;

/// Subscriber options for the loop topics: no Nagle delay (a lockstep cycle waits for each message).
inline ros::TransportHints loopTransportHints() { return ros::TransportHints().tcpNoDelay(); }

/// Accumulates the samples of one output topic; flush() publishes them as one ArrayMsg (shared
/// pointer, so that nodelets in one manager pass it without copying).
template <typename ArrayMsg>
class BatchPublisher {
 public:
  using Sample = typename decltype(ArrayMsg::samples)::value_type;

  void advertise(ros::NodeHandle& nh, const std::string& topic) {
    publisher_ = nh.advertise<ArrayMsg>(topic, kLoopQueueSize);
  }
  void add(Sample&& sample) {
    if (!pending_) {
      pending_ = boost::make_shared<ArrayMsg>();
      pending_->samples.reserve(16);
    }
    pending_->samples.push_back(std::move(sample));
  }
  std::size_t pendingSamples() const { return pending_ ? pending_->samples.size() : 0; }
  bool connected() const { return publisher_.getNumSubscribers() > 0; }
  int subscribers() const { return static_cast<int>(publisher_.getNumSubscribers()); }
  /// Publishes the pending samples, if any and if someone listens (a loop message published before
  /// its consumer connected would be lost, and the loop with it). Returns true if it published.
  bool flush() {
    if (!pending_ || pending_->samples.empty() || !connected()) return false;
    pending_->header = pending_->samples.back().header;
    publisher_.publish(boost::shared_ptr<const ArrayMsg>(pending_));
    pending_.reset();
    ++messages_;
    return true;
  }
  std::string topic() const { return publisher_.getTopic(); }
  std::uint64_t messages() const { return messages_; }

 private:
  ros::Publisher publisher_;
  boost::shared_ptr<ArrayMsg> pending_;
  std::uint64_t messages_ = 0;
};

/// Warns about rejected input (first occurrence at once, then at most once per second, with a count).
class RejectLog {
 public:
  void reject(const std::string& node, const std::string& topic, const std::string& why) {
    ++count_;
    const ros::WallTime now = ros::WallTime::now();
    if (count_ == 1 || (now - last_).toSec() >= 1.0) {
      ROS_WARN("%s: rejected a message on %s: %s; dropped, the loop state is unchanged (%llu rejected so far)",
               node.c_str(), topic.c_str(), why.c_str(), static_cast<unsigned long long>(count_));
      last_ = now;
    }
  }
  std::uint64_t count() const { return count_; }

 private:
  std::uint64_t count_ = 0;
  ros::WallTime last_;
};

/// "" if every sample of the array is finite, else which sample and field is not.
template <typename ArrayMsg>
std::string nonFiniteSample(const ArrayMsg& msg) {
  for (std::size_t i = 0; i < msg.samples.size(); ++i) {
    const std::string field = nonFiniteField(msg.samples[i]);
    if (!field.empty()) {
      return "sample " + std::to_string(i) + " of " + std::to_string(msg.samples.size()) + " (stamp " +
             std::to_string(msg.samples[i].header.stamp.toSec()) + " s) has " + field;
    }
  }
  return "";
}

/// Pushes every sample of `msg` through `push(stamp_ns, sample)`; a sample the core refuses
/// (InputError: stamp not newer than the last) is dropped with a warning, the rest go in.
template <typename ArrayMsg, typename Push>
void pushSamples(const ArrayMsg& msg, const std::string& node, const std::string& topic, RejectLog& log, Push push) {
  for (const auto& sample : msg.samples) {
    try {
      push(toNanoseconds(sample.header.stamp), sample);
    } catch (const InputError& e) {
      log.reject(node, topic, e.what());
    }
  }
}

}  // namespace lane_keeping
