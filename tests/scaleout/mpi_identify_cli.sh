#!/usr/bin/env bash
# End to end: `mpirun -np 3 demfit identify STUDY --mpi` with worker rank 2 killed on its third run
# reaches the same best parameters (byte-identical JSON) as `demfit identify STUDY --jobs 2`;
# then the MPI study is killed as a whole job mid-run and --resume completes it to the same answer.
#   mpi_identify_cli.sh DEMFIT STUDY WORKDIR
set -euo pipefail
demfit="$1"; study="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun_cmd=(mpirun --oversubscribe --enable-recovery -np 3)
"$demfit" identify "$study" --out "$work/jobs" --jobs 2 --no-plots > "$work/jobs.log" 2>&1
DEMFIT_TEST_FAULT=kill DEMFIT_TEST_FAULT_RANK=2 DEMFIT_TEST_FAULT_AFTER=3 \
  "${mpirun_cmd[@]}" "$demfit" identify "$study" --out "$work/mpi" --mpi --run-timeout 5 --no-plots \
  > "$work/mpi.log" 2>&1
grep -q "retired" "$work/mpi.log" || { echo "FAIL: the killed worker was not retired"; cat "$work/mpi.log"; exit 1; }
cmp "$work/jobs/best_parameters.json" "$work/mpi/best_parameters.json" \
  || { echo "FAIL: --mpi answer differs from --jobs"; exit 1; }
# Whole-job kill: every rank hangs on its 4th run, the job is killed, then resumed (no fault).
DEMFIT_TEST_FAULT=hang DEMFIT_TEST_FAULT_RANK=1 DEMFIT_TEST_FAULT_AFTER=4 \
  timeout -s KILL 8 "${mpirun_cmd[@]}" "$demfit" identify "$study" --out "$work/killed" --mpi --no-plots \
  > "$work/killed.log" 2>&1 || true
pkill -KILL -f "demfit identify $study --out $work/killed" || true
test -f "$work/killed/study.db" || { echo "FAIL: no store after the kill"; exit 1; }
"${mpirun_cmd[@]}" "$demfit" identify "$study" --out "$work/killed" --mpi --resume --no-plots > "$work/resumed.log" 2>&1
cmp "$work/jobs/best_parameters.json" "$work/killed/best_parameters.json" \
  || { echo "FAIL: resumed MPI study differs"; exit 1; }
echo "3 passed, 0 failed"
