#!/bin/bash
# For docs/measurements/README.md Table 3 reading 13: one run of the s = 4 SCG Table 3 drum at a study's
# answer (its best_parameters.json), printing NORMK, the drum summary's end-time particle overlap,
# mean drive torque and repose angle (neither is fitted: compare them with the s = 1 run's summary),
# and the surface RMS against the target (surface_offset.py). Writes only inside WORK.
# Usage: answer_overlap.sh DEMFIT STUDY_OUT_DIR TARGET_CSV WORK
#   e.g. answer_overlap.sh build/apps/demfit /tmp/t3v/out/table3/study /tmp/t3v/out/table3/target_free_surface.csv /tmp/ov
set -eu
demfit=$1 study=$2 target=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
cases=$(cd "$here/../../cases" && pwd)
mapfile -t values < <(python3 -c "
import json, sys
answer = json.load(open(sys.argv[1]))
for name, v in sorted(answer['variables'].items()):
    print('%s=%.17g' % (name, v['value']))" "$study/best_parameters.json")
"$demfit" simulate "$cases/rotary_drum.json" --set drum.coarse_graining=scg drum.scale_factor=4 "${values[@]}" \
  --out "$work" > /dev/null 2>&1
printf '%s  ' "$(printf '%s\n' "${values[@]}" | grep '^normk=')"
grep -E "particle overlap|mean drive torque|angle of repose" "$work/summary.txt" | sed 's/  */ /g'
python3 "$here/surface_offset.py" "$target" "$work/free_surface.csv" | sed -n 1p
