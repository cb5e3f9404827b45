#!/bin/bash
# For docs/measurements/README.md Table 3 reading 14: does a study's answer carry over to another drum
# condition? Runs replicate_surface.sh (8 round-off replicates of the s = 4 SCG drum, NDAMP nudged)
# at the answer of STUDY_OUT_DIR (its best_parameters.json; NDAMP cut to 8 digits so the nudges
# act) with the given case overrides, against a target computed at that condition. With STUDY_OUT_DIR
# "initial" it runs the case's own (initial) values. Writes only inside WORK.
# Usage: answer_transfer.sh DEMFIT STUDY_OUT_DIR|initial TARGET_CSV WORK [case.key=value ...]
#   e.g. answer_transfer.sh build/apps/demfit /tmp/t3v/out/table3/study /tmp/s1_30rpm/free_surface.csv /tmp/tr drum.rpm=30
set -eu
demfit=$1 study=$2 target=$3 work=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
if [ "$study" = initial ]; then
  # the case's own NDAMP, written to 8 digits like an answer's
  values=("$(python3 -c "import json, sys; print('%.8f' % json.load(open(sys.argv[1]))['contact']['ndamp'])" \
    "$here/../../cases/rotary_drum.json")")
else
  mapfile -t values < <(python3 -c "
import json, sys
answer = json.load(open(sys.argv[1]))['variables']
print('%.8f' % answer['ndamp']['value'])
for name, v in sorted(answer.items()):
    if name != 'ndamp':
        print('%s=%.17g' % (name, v['value']))" "$study/best_parameters.json")
fi
"$here/replicate_surface.sh" "$demfit" "$target" "$work" "${values[@]}" "$@"
