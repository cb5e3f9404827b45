// Bounded-spin OpenMP waiting by re-execution; see openmp_waiting.hpp.
#include "demfit/dem_core/openmp_waiting.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace demfit::dem_core {

void use_bounded_spin_waiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;  // user's choice
  if (setenv("GOMP_SPINCOUNT", kDefaultSpinCount, 0) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure
  const std::string what = std::string(argv[0] != nullptr ? argv[0] : "program") +
                           ": re-executing with GOMP_SPINCOUNT set failed; running with libgomp's default waiting";
  std::perror(what.c_str());
}

std::string openmp_waiting_description() {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  const char* spins = std::getenv("GOMP_SPINCOUNT");
  return std::string("OMP_WAIT_POLICY=") + (policy ? policy : "unset") +
         ", GOMP_SPINCOUNT=" + (spins ? spins : "unset");
}

}  // namespace demfit::dem_core
