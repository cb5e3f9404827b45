#!/bin/bash
# How well does the Table 1 pressure-volume curve tell points along the NORMK-SHEARK valley apart?
# Runs `demfit simulate` of the Table 1 case (cases/pellet_compression.json, max_travel 4.5 mm as in
# cases/table1_study.json) on a grid of NORMK x SHEARK, each point REPLICATES times with NORMK
# nudged by k * 1e-7 (other round-off trajectories of the same physics, as the study's replicates),
# two runs at a time on one thread each, and prints per point the mean and standard deviation of
# the mean squared pressure misfit [MPa^2] against the synthetic measured curve at its 60 volumes
# (linear interpolation of the simulated curve), with the NORMK error against the generating 0.875046.
# Usage: table1_valley.sh DEMFIT WORK "NORMK ..." "SHEARK ..." REPLICATES
#   e.g. table1_valley.sh build/apps/demfit /tmp/valley "0.86 0.875 0.89 0.905" "0.17 0.30 0.45" 4
set -eu
demfit=$1 work=$2 normks=$3 shearks=$4 replicates=$5
repo=$(cd "$(dirname "$0")/../.." && pwd)
# Only plain numbers reach the commands below (they become file names and --set values).
number='^[0-9]+([.][0-9]+)?$'
for value in $normks $shearks $replicates; do
  [[ $value =~ $number ]] || { echo "table1_valley.sh: '$value' is not a plain number" >&2; exit 1; }
done
mkdir -p "$work"
jobs=()
for n in $normks; do
  for s in $shearks; do
    for k in $(seq 0 $((replicates - 1))); do
      nudged=$(python3 -c 'import sys; print(repr(float(sys.argv[1]) + int(sys.argv[2]) * 1e-7))' "$n" "$k")
      jobs+=("$n $s $k $nudged")
    done
  done
done
# The paths go to the child shells as environment variables, not spliced into their script.
export VALLEY_WORK=$work VALLEY_DEMFIT=$demfit VALLEY_REPO=$repo
printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 bash -c '
  out="$VALLEY_WORK/n$0_s$1_r$2"
  [ -f "$out/pressure_volume.csv" ] && exit 0
  rm -rf "$out"
  "$VALLEY_DEMFIT" simulate "$VALLEY_REPO/cases/pellet_compression.json" --threads 1 --out "$out" \
    --set normk=$3 sheark=$1 pellet.max_travel=0.0045 > "$out.log" 2>&1 || { echo "simulate failed: $out.log" >&2; exit 255; }'
python3 - "$work" "$repo/data/pellet_pressure_volume_synthetic.csv" "$normks" "$shearks" "$replicates" <<'PY'
import bisect, csv, statistics, sys
work, target_csv, normks, shearks, replicates = sys.argv[1], sys.argv[2], sys.argv[3].split(), sys.argv[4].split(), int(sys.argv[5])
def read(path):
    rows = list(csv.reader(l for l in open(path) if not l.startswith("#")))
    header = rows[0]
    iv, ip = header.index("volume_cm3"), header.index("pressure_MPa")
    return [(float(r[iv]), float(r[ip])) for r in rows[1:]]
target = read(target_csv)
def mse(curve):
    curve = sorted(curve)
    xs = [v for v, _ in curve]; ys = [p for _, p in curve]
    total, count = 0.0, 0
    for x, y in target:
        if x < xs[0] or x > xs[-1]: continue
        i = max(1, bisect.bisect_left(xs, x))
        value = ys[i - 1] + (ys[i] - ys[i - 1]) * (x - xs[i - 1]) / (xs[i] - xs[i - 1])
        total += (value - y) ** 2; count += 1
    return total / count
print("NORMK     error    SHEARK  misfit mean [MPa^2]  sd       min      replicates")
for s in shearks:
    for n in normks:
        values = [mse(read("%s/n%s_s%s_r%d/pressure_volume.csv" % (work, n, s, k))) for k in range(replicates)]
        print("%-8s %+6.2f %%  %-6s  %.5f              %.5f  %.5f  %s" % (n, 100 * (float(n) / 0.875046 - 1), s,
              statistics.mean(values), statistics.stdev(values) if len(values) > 1 else 0.0, min(values),
              " ".join("%.5f" % v for v in values)))
PY
