#!/bin/bash
# The scratch replicates of docs/measurements/README.md reading 7 ("for comparison"): 8 runs of the s = 4
# SCG Table 3 drum at the given values, NDAMP nudged in its 8th-10th digit per run (another
# round-off trajectory), each scored by surface_offset.py (RMS [mm] over the target abscissae the
# curve spans); prints mean, sd, min, max.
# Usage: replicate_surface.sh DEMFIT TARGET_CSV WORK_DIR NDAMP [name=value ...]
#   e.g. replicate_surface.sh build/apps/demfit results/table3/target_free_surface.csv /tmp/rep 0.87884 \
#          tdamp=0.116648 frics=0.01 fricr=0.3 normk=0.003 sheark=0.0003 wall_frics=0.478453 wall_fricd=0 wall_damp=0.05
set -eu
demfit=$1 target=$2 work=$3 ndamp=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
cases=$(cd "$here/../../cases" && pwd)
mkdir -p "$work"
values=()
for k in 1 2 3 4 5 6 7 8; do
  out="$work/run_$k"
  "$demfit" simulate "$cases/rotary_drum.json" --set drum.coarse_graining=scg drum.scale_factor=4 "$@" \
    "ndamp=${ndamp}00$k" --out "$out" > /dev/null
  values+=("$(python3 "$here/surface_offset.py" "$target" "$out/free_surface.csv" | sed -n 's/^RMS \([0-9.]*\) mm.*/\1/p')")
done
python3 -c "
import statistics as s, sys
v = [float(x) for x in sys.argv[1:]]
print('mean %.2f sd %.2f min %.2f max %.2f n %d' % (s.mean(v), s.stdev(v), min(v), max(v), len(v)))" "${values[@]}"
