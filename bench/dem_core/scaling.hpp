#pragma once
// Scaling table: particle-steps/s (1 and 2 threads) and peak memory per particle for boxes of
// ~10^3 .. 10^6 spheres. Each size runs in a fresh child process (this benchmark re-executed with
// --scaling-child), so its peak resident set (wait4's ru_maxrss) belongs to that size alone.
#include <cstddef>
#include <string>
#include <vector>

namespace demfit::bench {

struct ScalingOptions {
  std::vector<std::size_t> sizes{1000, 10000, 100000, 1000000};
  double work = 1.0e7;  ///< particle-steps per timed run (steps = max(work / N, 10))
  int repeats = 3;
  bool shuffled = true;  ///< particles inserted in a seeded random order (a mixed bed) vs lattice order
};

void print_scaling_table(const ScalingOptions& options);

/// Body of the child process: builds the box, times it, prints one "scaling-result ..." line.
int run_scaling_child(std::size_t particles, long steps, int repeats, bool shuffled, const std::string& order);

}  // namespace demfit::bench
