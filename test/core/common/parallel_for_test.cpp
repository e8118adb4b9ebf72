// The worker pool (common/parallel_for.h): every index once, on several threads, and an exception in a
// job reaches the caller instead of ending the process.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "lane_keeping/common/parallel_for.h"

namespace lane_keeping {
namespace {

TEST(ParallelFor, RunsEveryIndexOnceOnTheThreadsAsked) {
  std::vector<std::atomic<int>> runs(100);
  std::mutex mutex;
  std::set<std::thread::id> workers;
  parallelFor(runs.size(), 3, [&](std::size_t i) {
    ++runs[i];
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    std::lock_guard<std::mutex> lock(mutex);
    workers.insert(std::this_thread::get_id());
  });
  for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].load(), 1) << i;
  EXPECT_GE(workers.size(), 2u);
  EXPECT_LE(workers.size(), 3u);
}

TEST(ParallelFor, OneThreadRunsTheJobsInOrderOnTheCaller) {
  // (A line search's grid on one thread: no thread started per grid.)
  std::vector<std::size_t> order;
  std::set<std::thread::id> workers;
  parallelFor(20, 1, [&](std::size_t i) {
    order.push_back(i);
    workers.insert(std::this_thread::get_id());
  });
  ASSERT_EQ(order.size(), 20u);
  for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
  EXPECT_EQ(workers, std::set<std::thread::id>{std::this_thread::get_id()});
}

TEST(ParallelFor, AnExceptionReachesTheCallerAfterEveryOtherIndexRan) {
  // Two jobs throw: the lowest index's exception is the one rethrown, whichever thread finished first,
  // and the jobs that did not throw all ran.
  for (int threads : {1, 2, 4}) {
    std::atomic<int> ran{0};
    try {
      parallelFor(40, threads, [&](std::size_t i) {
        if (i == 7 || i == 30) throw std::runtime_error("job " + std::to_string(i));
        ++ran;
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "job 7") << threads;
    }
    EXPECT_EQ(ran.load(), 38) << threads;
  }
}

}  // namespace
}  // namespace lane_keeping
