#pragma once
/// Large buffers written once right after they are allocated (a lane of 10^5 points, its spline).
/// Fresh memory costs a page fault per 4 KiB page on first write: ~12 us each on the 2-core virtual
/// machine the benchmarks run on (about 0.2 us on bare metal), so the 3 MB of a 10^5-point lane cost
/// ~10 ms of faults - more than reading and solving it (issue 18, bench/lane_length.py). Asking the kernel
/// to populate a buffer's pages in one call (MADV_POPULATE_WRITE, Linux 5.14) costs a third of that. It
/// changes no value, only when the pages are mapped; where the call is unknown it does nothing.
#include <cstddef>
#include <vector>

namespace lane_keeping {

/// Maps the whole pages in [data, data + bytes) now, if at least kMinBytes (smaller ones fault a few
/// pages at most, fewer than a system call saves).
void populatePages(void* data, std::size_t bytes);
inline constexpr std::size_t kPopulateMinBytes = 256 * 1024;

/// A vector of n default values (value-initialised, as std::vector(n)) whose pages are mapped in one call.
template <typename T>
std::vector<T> populatedVector(std::size_t n, const T& value = T()) {
  std::vector<T> v;
  v.reserve(n);
  populatePages(v.data(), n * sizeof(T));
  v.assign(n, value);
  return v;
}

}  // namespace lane_keeping
