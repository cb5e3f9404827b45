#include "bench_timing.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include <sys/mman.h>
#include <sys/resource.h>

namespace demfit::bench {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string load_average() {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) != 3) return "load ?";
  char text[64];
  std::snprintf(text, sizeof text, "load %.2f %.2f %.2f", load[0], load[1], load[2]);
  return text;
}

std::uint64_t minor_page_faults() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_minflt);
}

double fresh_page_microseconds() {
  constexpr std::size_t kBytes = 280 * 1024, kPage = 4096;
  constexpr int kRounds = 500;
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < kRounds; ++r) {
    void* block = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (block == MAP_FAILED) return 0.0;
    auto* bytes = static_cast<volatile char*>(block);
    for (std::size_t k = 0; k < kBytes; k += kPage) bytes[k] = 1;
    munmap(block, kBytes);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return seconds / kRounds / static_cast<double>(kBytes / kPage) * 1e6;
}

double wall_seconds_for_steps(dem_core::Simulation& sim, std::uint64_t steps) {
  const auto start = std::chrono::steady_clock::now();
  sim.run_steps(steps);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace demfit::bench
