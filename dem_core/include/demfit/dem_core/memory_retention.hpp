#pragma once
// Freed memory kept in the process. Every neighbour-list rebuild frees its old pair
// arrays and the scratch of the particle reordering, and allocates new ones of about the same
// size. glibc returns large freed blocks to the kernel (a block above its mmap threshold is
// unmapped; the heap top above its trim threshold is released), so the next rebuild takes fresh
// pages, and each fresh page is a page fault. On this project's machines (virtual machines) one
// costs 9-12 µs; bench_dem --only drum prints the cost and each run's faults: in the cases' pair
// order (own_row_first) a 10,000-step drum run on 1 thread took 15,401 faults with glibc's
// defaults and 365 with the retention (bench/dem_core/measured/drum_2026-12-04_ab_retention.txt).
// Peak memory at 10^6 particles with it: 463 (default order) and 757 (own_row_first) bytes per
// particle, against 466 and 734 before the change (scaling_2026-12-04_eighteenth.txt,
// scaling_2026-12-04_slab_order.txt): the cases' order keeps ~23 bytes per particle more.
namespace demfit::dem_core {

/// glibc only (elsewhere nothing changes): blocks below 32 MiB come from the heap, and up to
/// 256 MiB of free heap is kept instead of being returned. A program setting; call first thing
/// in main. Returns false when the C library refused (then its defaults stay).
bool retain_freed_memory();

}  // namespace demfit::dem_core
