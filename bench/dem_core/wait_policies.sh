#!/bin/bash
# The issue-16 drum (demfit only, 2 threads, stored and Morton-reordered particle order) under
# four OpenMP waiting settings: passive (no spin), GOMP_SPINCOUNT 30,000 (demfit's default,
# dem_core/openmp_waiting.hpp), 300,000 (libgomp's default) and active. libgomp reads them when it
# loads, so each setting is a separate process (which prepares its own bed: ~2 min each).
# Usage: bench/dem_core/wait_policies.sh BUILD_DIR [STEPS (5000)] [REPEATS (3)]
# Time it only when nothing else runs (README "Performance").
set -euo pipefail
bench="$1/bench/dem_core/bench_dem"
steps="${2:-5000}"
repeats="${3:-3}"
for setting in "passive:" "passive:30000" "passive:300000" "active:"; do
  policy="${setting%%:*}"
  spins="${setting##*:}"
  echo "=== OMP_WAIT_POLICY=$policy GOMP_SPINCOUNT=${spins:-(the policy's default)}"
  if [ -n "$spins" ]; then
    OMP_WAIT_POLICY="$policy" GOMP_SPINCOUNT="$spins" "$bench" --only drum --no-liggghts --steps "$steps" --repeats "$repeats"
  else
    env -u GOMP_SPINCOUNT OMP_WAIT_POLICY="$policy" "$bench" --only drum --no-liggghts --steps "$steps" --repeats "$repeats"
  fi | grep -E "thread|medians|speed-up|reorder_particles \("
done
