// retain_freed_memory (memory_retention.hpp): a block freed and allocated again, as a neighbour-list
// rebuild does with its pair arrays, comes back without fresh pages from the kernel.
#include <sys/resource.h>

#include <catch2/catch.hpp>
#include <cstddef>
#include <vector>

#include "demfit/dem_core/memory_retention.hpp"

namespace {

long minor_page_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

}  // namespace

TEST_CASE("A block freed and allocated again costs no fresh pages once freed memory is retained") {
  if (!demfit::dem_core::retain_freed_memory()) {
    // A sanitizer's allocator (or another C library) ignores glibc's thresholds.
    WARN("retain_freed_memory: the C library refused the thresholds; nothing to check here");
    return;
  }
  constexpr std::size_t kBytes = std::size_t{8} << 20;  // 2,048 pages: above glibc's first mmap threshold
  {
    std::vector<char> first(kBytes, 1);
    REQUIRE(first[kBytes - 1] == 1);
  }
  const long before = minor_page_faults();
  {
    std::vector<char> second(kBytes, 2);
    REQUIRE(second[kBytes - 1] == 2);
  }
  // glibc's defaults would unmap the first block and fault in all 2,048 pages of the second.
  CHECK(minor_page_faults() - before < 64);
}
