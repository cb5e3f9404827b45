#!/usr/bin/env bash
# MPI throughput benchmark: a fixed batch of CPU-bound evaluations with 1, 2 and 3
# ranks on this machine, the measured ratios, and a projection for a cluster.
#   bench/scaleout/run_bench.sh [BUILD_DIR] [RUNS] [SECONDS_PER_RUN]
set -euo pipefail
build="${1:-build}"; runs="${2:-12}"; per_run="${3:-0.5}"
exe="$build/bench/scaleout/bench_mpi_throughput"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
declare -A rate
for ranks in 1 2 3; do
  line=$(mpirun --oversubscribe --enable-recovery -np "$ranks" "$exe" "$runs" "$per_run" 2>/dev/null | grep '^ranks')
  echo "$line"
  rate[$ranks]=$(echo "$line" | awk '{print $8}')
  per_run_measured=$(echo "$line" | awk '{print $10}')
done
awk -v r1="${rate[1]}" -v r2="${rate[2]}" -v r3="${rate[3]}" -v t="$per_run_measured" -v n="$runs" 'BEGIN {
  printf "throughput ratio 2 ranks / 1 rank: %.2f (1 worker: rank 0 only schedules)\n", r2 / r1;
  printf "throughput ratio 3 ranks / 1 rank: %.2f (2 workers on 2 cores)\n", r3 / r1;
  # Overhead per run from the 3-rank run: time beyond ideal 2-way parallel execution.
  overhead = (n / r3 - n * t / 2) / (n / 2); if (overhead < 0) overhead = 0;
  printf "measured per-run time %.3f s, scheduling overhead per run %.4f s\n", t, overhead;
  print "projected speed-up on a cluster, W workers, batches of P points per iteration:";
  print "  (the loop waits for each batch: speed-up = P / ceil(P/W) x t/(t+overhead))";
  split("3878 390", times, " ");
  for (k in times) {
    T = times[k];
    printf "  per-run %5d s (paper %s):", T, (k == 1 ? "mean" : "min");
    split("4 8 16 32", ws, " ");
    for (j = 1; j <= 4; ++j) { W = ws[j]; P = 16; b = int((P + W - 1) / W);
      printf "  W=%d: %.1fx", W, P / b * T / (T + overhead); }
    printf "\n";
  }
}'
