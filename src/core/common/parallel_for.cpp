#include "lane_keeping/common/parallel_for.h"

#include <algorithm>
#include <mutex>
#include <thread>
#include <vector>

namespace lane_keeping {

void parallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& body,
                 const std::function<void(std::size_t)>& announce) {
  std::mutex mutex;
  std::size_t next = 0;
  auto worker = [&]() {
    while (true) {
      std::size_t index;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (next >= count) return;
        index = next++;
        if (announce) announce(index);
      }
      body(index);
    }
  };
  std::vector<std::thread> pool;
  const std::size_t n = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(std::max(1, threads)), count));
  for (std::size_t i = 0; i < n; ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
}

}  // namespace lane_keeping
