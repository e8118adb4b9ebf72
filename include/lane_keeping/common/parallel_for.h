#pragma once
/// A minimal worker pool for independent jobs (candidate fits, noise-reference draws).
#include <cstddef>
#include <functional>

namespace lane_keeping {

/// Runs body(0) .. body(count - 1) on up to `threads` threads (each index once, in any order);
/// `announce(i)`, if given, runs under a lock just before body(i) (progress messages). An exception
/// from body(i) does not stop the others; once all have run, the one of the lowest index is rethrown.
/// With one thread (or one job) the jobs run on the calling thread, in index order.
void parallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& body,
                 const std::function<void(std::size_t)>& announce = nullptr);

}  // namespace lane_keeping
