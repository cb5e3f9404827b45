#pragma once
// How idle OpenMP threads wait at the three barriers of every step. libgomp reads
// OMP_WAIT_POLICY and GOMP_SPINCOUNT once, when it is loaded — before main — so a program that
// wants a default of its own must set it and re-execute itself; a setenv in main is silently
// ignored (demfit's CLI did exactly that until this change, and ran on libgomp's default).
//
// The default chosen here, a bounded spin of 30,000 iterations (libgomp's estimate: ~0.3 ms)
// before sleeping, was measured on the issue-16 drum (6,996 spheres, Morton-reordered, 2 threads,
// medians of 3; bench/dem_core/measured/wait_policy_2026-12-02.txt): 8.88 M particle-steps/s with
// passive waiting (no spin), 9.86 M with 30,000 spins, 9.98 M fully active. Passive waiting loses
// ~10 % at every barrier's wake-up; unbounded spinning made 2 threads 5-10x slower than 1 on a
// loaded machine (a preempted partner). The bounded spin covers a barrier's usual wait and then
// gives the core away.
#include <string>

namespace demfit::dem_core {

inline constexpr const char* kDefaultSpinCount = "30000";

/// If the user set neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT: sets GOMP_SPINCOUNT to
/// kDefaultSpinCount and re-executes /proc/self/exe with the same arguments, so that libgomp
/// starts with it. Call first thing in main. Returns only when nothing needed changing or the
/// re-execution failed (then libgomp's own default stays, and a note goes to stderr).
void use_bounded_spin_waiting(char** argv);

/// The waiting in effect, for logs and benchmarks: "OMP_WAIT_POLICY=..., GOMP_SPINCOUNT=..."
/// (each "unset" when not in the environment, i.e. libgomp's default).
std::string openmp_waiting_description();

}  // namespace demfit::dem_core
