// glibc's malloc thresholds; see memory_retention.hpp.
#include "demfit/dem_core/memory_retention.hpp"

#include <cstdlib>  // defines __GLIBC__ when the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace demfit::dem_core {

bool retain_freed_memory() {
#if defined(__GLIBC__)
  // 32 MiB is glibc's ceiling for the mmap threshold on 64-bit systems; setting either value
  // also stops glibc from moving both thresholds by itself (its dynamic adjustment, which reached
  // ~20 faults per rebuild on the issue-16 drum).
  constexpr int kMmapThreshold = 32 << 20;
  constexpr int kTrimThreshold = 256 << 20;
  return mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1 && mallopt(M_TRIM_THRESHOLD, kTrimThreshold) == 1;
#else
  return false;
#endif
}

}  // namespace demfit::dem_core
