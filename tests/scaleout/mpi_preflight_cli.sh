#!/usr/bin/env bash
# `mpirun -np 3 demfit identify STUDY --mpi` checks the study at the initial point, evaluated on a
# worker rank, before anything is created, as without MPI: a target naming a curve the
# model does not produce ends the whole job with one error line listing the model's curves, a
# non-zero exit, and no output folder. (Without --enable-recovery: Open MPI 4.1's mpirun with it
# exits 0 whatever its processes return, even `mpirun --enable-recovery -np 3 sh -c 'exit 3'`.)
#   mpi_preflight_cli.sh DEMFIT STUDY WORKDIR
set -euo pipefail
demfit="$1"; study="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cp "$(dirname "$study")"/analytic_target.csv "$work/"
sed 's/"curve": "response"/"curve": "pressure_volume"/' "$study" > "$work/study.json"
grep -q '"curve": "pressure_volume"' "$work/study.json" || { echo "FAIL: could not make the bad study"; exit 1; }
status=0
(cd "$work" && timeout -s KILL 60 mpirun --oversubscribe -np 3 "$demfit" identify study.json \
  --out out --mpi --no-plots > mpi.log 2>&1) || status=$?
[ "$status" -ne 0 ] || { echo "FAIL: exit status 0"; cat "$work/mpi.log"; exit 1; }
[ "$status" -ne 137 ] || { echo "FAIL: the job hung and was killed"; cat "$work/mpi.log"; exit 1; }
grep -q "demfit: error: study: targets\[0\].curve: 'pressure_volume' is not a curve of model 'analytic'; it produces: loop, response" \
  "$work/mpi.log" || { echo "FAIL: no one-line error naming the curve"; cat "$work/mpi.log"; exit 1; }
[ ! -e "$work/out" ] || { echo "FAIL: the output folder was created"; exit 1; }
echo "3 passed, 0 failed"
