#pragma once
/// The two thin shells every role (class per role, built from the node handle and the private node
/// handle) runs in: a standalone node (runNode, for *_node.cpp) and a nodelet (NodeletShell, for
/// *_nodelet.cpp). A bad configuration stops either with the core's message naming every key:
/// the node exits with status 2, the nodelet shuts its manager down (the launch fails).
///
/// Nodelets of this package in one manager share one thread by default (private parameter
/// shared_thread): a lockstep cycle is then a chain of callbacks in that thread, with no thread
/// wake-up between the plant and the controllers (each costs tens of microseconds). Messages still
/// go over the topics (intra-process, zero copy); other subscribers (rosbag, rviz) are unaffected.
#include <atomic>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>

#include <nodelet/nodelet.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <thread>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {

template <typename Role, typename = void>
struct HasExitCode : std::false_type {};
template <typename Role>
struct HasExitCode<Role, std::void_t<decltype(std::declval<const Role&>().exitCode())>> : std::true_type {};

template <typename Role>
int runNode(int argc, char** argv, const char* default_name) {
  ros::init(argc, argv, default_name);
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  const std::string name = ros::this_node::getName();
  std::unique_ptr<Role> role;
  try {
    role = std::make_unique<Role>(nh, pnh, name);
  } catch (const LaneKeepingError& e) {
    ROS_FATAL("%s: %s", name.c_str(), e.what());
    std::cerr << name << ": " << e.what() << std::endl;
    return 2;
  }
  ros::spin();
  if constexpr (HasExitCode<Role>::value) {
    return role->exitCode() < 0 ? 0 : role->exitCode();
  }
  return 0;
}

/// One callback queue and one thread for every lane_keeping nodelet in the process that asks for it.
class SharedExecutor {
 public:
  /// The process's executor, created on first use; it stops when the last user releases it.
  static std::shared_ptr<SharedExecutor> acquire() {
    static std::mutex mutex;
    static std::weak_ptr<SharedExecutor> current;
    std::lock_guard<std::mutex> lock(mutex);
    std::shared_ptr<SharedExecutor> executor = current.lock();
    if (!executor) {
      executor.reset(new SharedExecutor);
      current = executor;
    }
    return executor;
  }
  ~SharedExecutor() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  ros::CallbackQueue* queue() { return &queue_; }

 private:
  SharedExecutor() : thread_([this] {
    while (running_ && ros::ok()) queue_.callAvailable(ros::WallDuration(0.05));
  }) {}
  ros::CallbackQueue queue_;
  std::atomic<bool> running_{true};
  std::thread thread_;
};

/// Whether a role's nodelet joins the shared thread when the `shared_thread` parameter is not set:
/// the loop's roles do; a role that only watches the loop (the gap monitor) specialises it to false.
template <typename Role>
struct SharedThreadDefault : std::true_type {};

template <typename Role>
class NodeletShell : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle nh = getNodeHandle();
    ros::NodeHandle pnh = getPrivateNodeHandle();
    bool shared_thread = SharedThreadDefault<Role>::value;
    pnh.param("shared_thread", shared_thread, shared_thread);
    if (shared_thread) {
      executor_ = SharedExecutor::acquire();
      nh.setCallbackQueue(executor_->queue());
      pnh.setCallbackQueue(executor_->queue());
    }
    try {
      role_ = std::make_unique<Role>(nh, pnh, getName());
    } catch (const LaneKeepingError& e) {
      NODELET_FATAL("%s", e.what());
      std::cerr << getName() << ": " << e.what() << std::endl;
      ros::requestShutdown();
    }
  }
  std::shared_ptr<SharedExecutor> executor_;  // declared first: the role goes before its thread
  std::unique_ptr<Role> role_;
};

}  // namespace lane_keeping
