#pragma once
// Freed memory kept in the process (issue 16). Every neighbour-list rebuild frees its old pair
// arrays and the scratch of the particle reordering, and allocates new ones of about the same
// size. glibc returns large freed blocks to the kernel (a block above its mmap threshold is
// unmapped; the heap top above its trim threshold is released), so the next rebuild takes fresh
// pages, and each fresh page is a page fault. On this project's machines (virtual machines) one
// costs ~10 µs: bench_dem --only drum prints the cost and the faults per rebuild. Kept in the
// process, the freed blocks are reused and the faults stop; the peak memory is that of the
// largest rebuild, as before.
namespace demfit::dem_core {

/// glibc only (elsewhere nothing changes): blocks below 32 MiB come from the heap, and up to
/// 256 MiB of free heap is kept instead of being returned. A program setting; call first thing
/// in main. Returns false when the C library refused (then its defaults stay).
bool retain_freed_memory();

}  // namespace demfit::dem_core
