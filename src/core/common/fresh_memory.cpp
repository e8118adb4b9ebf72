#include "lane_keeping/common/fresh_memory.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>

namespace lane_keeping {

void populatePages(void* data, std::size_t bytes) {
#ifdef __linux__
  if (data == nullptr || bytes < kPopulateMinBytes) return;
#ifndef MADV_POPULATE_WRITE
  constexpr int MADV_POPULATE_WRITE = 23;  // linux/mman.h of Linux 5.14; older headers lack it
#endif
  static const std::uintptr_t page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + page - 1) / page * page;
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) / page * page;
  // Whole pages inside the buffer only: the partial ones at its ends may be another allocation's. The
  // result is ignored: EINVAL (an older kernel) or ENOMEM leave the pages to fault in on first write.
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace lane_keeping
