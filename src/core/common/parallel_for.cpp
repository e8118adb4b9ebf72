#include "lane_keeping/common/parallel_for.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace lane_keeping {

void parallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& body,
                 const std::function<void(std::size_t)>& announce) {
  std::mutex mutex;
  std::size_t next = 0;
  // An exception leaving body(i) on a worker would end the process (std::terminate): it is kept, the
  // other indices still run, and the one of the lowest index is rethrown here once all have.
  std::size_t failed_index = count;
  std::exception_ptr failure;
  auto worker = [&]() {
    while (true) {
      std::size_t index;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (next >= count) return;
        index = next++;
        if (announce) announce(index);
      }
      try {
        body(index);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (index < failed_index) {
          failed_index = index;
          failure = std::current_exception();
        }
      }
    }
  };
  const std::size_t n = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(std::max(1, threads)), count));
  if (n == 1) {
    worker();  // on the calling thread, in index order: no thread to start for a one-thread grid
  } else {
    std::vector<std::thread> pool;
    for (std::size_t i = 0; i < n; ++i) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace lane_keeping
