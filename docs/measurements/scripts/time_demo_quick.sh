#!/bin/bash
# Cold-cache wall time of `demfit reproduce all --quick` (the first part of scripts/demo), 3 runs one
# after another, each with a fresh result cache and output folder; prints each run's wall time and
# the load average before it (the first should be idle: run nothing else). Per-step times are in
# each output's report.md. For README "How long the main job takes here".
# Usage: time_demo_quick.sh DEMFIT
set -u
demfit=$1
for i in 1 2 3; do
  run=$(mktemp -d)  # everything of this run stays in it: cache, output folder, log
  cache=$run/cache out=$run/out
  mkdir "$cache"
  load=$(cut -d' ' -f1-3 /proc/loadavg)
  start=$(date +%s.%N)
  DEMFIT_CACHE_DIR=$cache "$demfit" reproduce all --quick --out "$out" > "$run/log" 2>&1
  status=$?
  end=$(date +%s.%N)
  echo "run $i exit $status wall $(python3 -c 'import sys; print("%.0f" % (float(sys.argv[2]) - float(sys.argv[1])))' "$start" "$end") s," \
    "load before $load, report $out/report.md"
done
