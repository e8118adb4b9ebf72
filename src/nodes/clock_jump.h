#pragma once
/// What a controller does when time jumps backwards: a bag played in a loop (`rosbag play --loop --clock`)
/// sends the loop's inputs again from its start, the ROS clock and the stamps going back together.
/// Without this, every sample of the second pass would be older than the last one of the first and be
/// rejected as stale: the node would warn once a second and never compute again. With it the node
/// restarts from its initial state (fresh delay lines, the integrator at zero, the configured runtime
/// changes scheduled again), so every pass through the bag gives the outputs of the first, and says so.
///
/// A stamp that goes back while the clock does not (a duplicated or stale message, rostest bad_stamps)
/// is rejected as before: only the clock decides. The node restarts at the first message of the new
/// pass (stamped more than kJump before the latest on its input) once the clock has gone back, so the
/// old pass's messages still on their way before it are computed in the old pass. The clock and the
/// inputs come over different connections: a message of the new pass that arrives before the node has
/// seen the clock go back is held (at most kHoldWall of wall time) until the clock confirms the jump,
/// or, if it does not, pushed as usual (and rejected as stale by the core). A node with two inputs (the
/// actuator) may restart on one while the other still brings the old pass's last samples: those
/// (stamped more than kJump after the clock the jump went to) are dropped with a warning, so a pass can
/// lose a few samples at its very end, never change one.
#include <cstddef>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "lane_keeping/common/time.h"
#include "loop_io.h"

namespace lane_keeping {

class ClockJumpGuard {
 public:
  static constexpr double kJump = 1.0;       // [s] a jump back by more is a new pass; the gap monitor's rule
  static constexpr double kHoldWall = 0.5;   // [s wall] how long a message waits for the clock to confirm
  static constexpr double kPendingWall = 1.0;  // [s wall] how long a clock jump waits for the new pass's input
  static constexpr std::size_t kMaxHeld = 10000;
  static constexpr Nanoseconds kNone = std::numeric_limits<Nanoseconds>::min();

  /// What the node does to restart: `flush` sends what it has produced, `rebuild` makes its core stage
  /// afresh (and forgets the latest stamps taken). `node`, `what` ("the path tracker") and `resets` (what
  /// a restart resets) go into the warning.
  void onRestart(std::string node, std::string what, std::string resets, std::function<void()> flush,
                 std::function<void()> rebuild) {
    node_ = std::move(node);
    what_ = std::move(what);
    resets_ = std::move(resets);
    flush_ = std::move(flush);
    rebuild_ = std::move(rebuild);
  }

  /// For a message on one input whose latest stamp taken since the (re)start is `latest`: true when it was
  /// dropped (as one of the pass before a jump, counted on `rejects`) or held (`take` runs on release);
  /// false when the caller takes it now, the node having restarted first if it begins a new pass.
  template <typename ArrayMsg>
  bool heldOrDropped(const ArrayMsg& msg, Nanoseconds latest, const std::string& topic, RejectLog& rejects,
                     std::function<void()> take) {
    const Nanoseconds first = msg->samples.empty() ? latest : toNanoseconds(msg->samples.front().header.stamp);
    switch (classify(first, latest)) {
      case Arrival::kDrop:
        rejects.reject(node_, topic, "stamped " + formatSeconds(nanosecondsToSeconds(first)) +
                                         ", a message of the pass before the clock jumped back");
        return true;
      case Arrival::kHold:
        hold(std::move(take));
        return true;
      case Arrival::kRestart:
        restart();
        return false;
      case Arrival::kTake:
        return false;
    }
    return false;
  }

  /// For the node's wall timer: restarts when held messages have since seen the clock jump back (they
  /// begin a new pass); releases them when they waited kHoldWall in vain (stale after all: the core
  /// rejects them).
  void onTimer() {
    if (heldAndJumped()) {
      restart();
    } else if (heldTooLong()) {
      release();
    }
  }

  /// From the initial state, after the ROS clock jumped back; then the held messages.
  void restart() {
    if (flush_) flush_();
    ++restarts_;
    const std::string jump = restarted();
    ROS_WARN("%s: the ROS clock jumped back %s (a bag played in a loop?): restarting %s from its initial state "
             "(pass %d; %s)",
             node_.c_str(), jump.c_str(), what_.c_str(), restarts_ + 1, resets_.c_str());
    if (rebuild_) rebuild_();
    release();  // the new pass's first messages, held until the clock confirmed the jump
  }

 private:

  /// What to do with a message on one input, whose first sample is stamped `first`, `latest` being the
  /// latest stamp the node took on that input since its (re)start.
  enum class Arrival {
    kTake,     ///< in sequence (or stale while the clock did not jump: the core rejects it)
    kRestart,  ///< the first of a new pass, the clock having jumped back: restart, release(), then take
    kHold,     ///< may be the first of a new pass the clock has not shown yet: hold() it
    kDrop,     ///< stamped after the jump target by more than kJump, arriving after the restart: the old pass's
  };
  Arrival classify(Nanoseconds first, Nanoseconds latest) {
    noticeClock();
    if (!ros::Time::isSimTime()) return Arrival::kTake;
    if (!restarted_wall_.isZero() && (ros::WallTime::now() - restarted_wall_).toSec() < kHoldWall &&
        first > secondsToNanoseconds(restarted_clock_ + kJump)) {
      return Arrival::kDrop;
    }
    if (latest == kNone || first >= latest - secondsToNanoseconds(kJump)) return Arrival::kTake;
    if (jumpPending()) return Arrival::kRestart;
    return held_.size() < kMaxHeld ? Arrival::kHold : Arrival::kTake;
  }

  /// For the node's timer: true when messages are held and the clock has since jumped back (restart,
  /// then release()); release() alone when they have waited kHoldWall in vain.
  bool heldAndJumped() {
    noticeClock();
    return holding() && jumpPending();
  }
  bool heldTooLong() const { return holding() && (ros::WallTime::now() - held_since_).toSec() >= kHoldWall; }
  bool holding() const { return !held_.empty(); }

  /// Keeps `process` (the message's normal handling) until release().
  void hold(std::function<void()> process) {
    if (held_.empty()) held_since_ = ros::WallTime::now();
    held_.push_back(std::move(process));
  }
  /// Handles the held messages in arrival order: after a restart they are the new pass's first; without
  /// one, the core rejects them as stale and the node counts them.
  void release() {
    std::vector<std::function<void()>> held;
    held.swap(held_);
    for (auto& process : held) process();
  }

  /// Call when the node restarts: the pending jump is consumed. Returns "from A s to B s".
  std::string restarted() {
    pending_wall_ = ros::WallTime();
    restarted_wall_ = ros::WallTime::now();
    restarted_clock_ = jumped_to_;
    char text[96];
    std::snprintf(text, sizeof(text), "from %.3f s to %.3f s", jumped_from_, jumped_to_);
    return text;
  }

  /// Notes the ROS clock (simulated time only) going back by more than kJump since the latest it showed.
  void noticeClock() {
    if (!ros::Time::isSimTime()) return;
    const double now = ros::Time::now().toSec();
    if (now < latest_clock_ - kJump) {
      jumped_from_ = latest_clock_;
      jumped_to_ = now;
      pending_wall_ = ros::WallTime::now();
      latest_clock_ = now;
    } else if (now > latest_clock_) {
      latest_clock_ = now;
    }
  }
  bool jumpPending() const {
    return !pending_wall_.isZero() && (ros::WallTime::now() - pending_wall_).toSec() < kPendingWall;
  }

  std::string node_, what_, resets_;
  std::function<void()> flush_, rebuild_;
  int restarts_ = 0;  // passes started over (the warning numbers the pass)
  double latest_clock_ = -std::numeric_limits<double>::infinity();
  double jumped_from_ = 0.0, jumped_to_ = 0.0;
  ros::WallTime pending_wall_;    // when the clock jumped, until the new pass's first input restarts the node
  ros::WallTime restarted_wall_;  // when the node last restarted
  double restarted_clock_ = 0.0;
  std::vector<std::function<void()>> held_;
  ros::WallTime held_since_;
};

}  // namespace lane_keeping
